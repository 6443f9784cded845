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


def mesh_and_write(script, output, order, size, surfaces, needed, volumes):
    """Checks every `needed` surface group was found (exits naming the first missing),
    meshes with sizes in [0.3 size, size], raises to `order` and writes (above)."""
    import sys
    for name in needed:
        if name not in surfaces:
            sys.exit(f"{script}: no surface classified as {name}")
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.option.setNumber("Mesh.MeshSizeMin", 0.3 * size)
    gmsh.model.mesh.generate(3)
    if order == 2:
        raise_to_quadratic()
    write_physical_groups(output, order, surfaces, volumes)
