"""What the mesh scripts share: raising a Gmsh mesh to order 2 and writing its physical
groups as MSH 4.1 ASCII, the format fe2heart's read_gmsh_tets reads."""
import gmsh


def raise_to_quadratic():
    """Order 2 with the edge nodes on the CAD surfaces; curved nodes can fold a thin
    element inside out, so untangle them (elastic analogy, then optimization of the
    scaled Jacobians)."""
    gmsh.option.setNumber("Mesh.HighOrderOptimize", 2)
    gmsh.model.mesh.setOrder(2)
    gmsh.model.mesh.optimize("HighOrder")


def write_physical_groups(output, order, surfaces, volumes):
    """surfaces: name -> surface tags; volumes: (name, volume tags, physical tag or -1 for
    Gmsh's choice), in order. Writes only the physical groups and prints a summary."""
    for name in sorted(surfaces):
        gmsh.model.setPhysicalName(2, gmsh.model.addPhysicalGroup(2, surfaces[name]), name)
    for name, tags, tag in volumes:
        gmsh.model.setPhysicalName(3, gmsh.model.addPhysicalGroup(3, tags, tag), name)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 0)
    gmsh.option.setNumber("Mesh.SaveAll", 0)  # only the physical groups
    gmsh.write(output)
    print(f"{output}: order {order}, {len(gmsh.model.mesh.getNodes()[0])} nodes, "
          f"surfaces {', '.join(f'{n} ({len(t)})' for n, t in sorted(surfaces.items()))}")
