#pragma once
// An idealized left ventricle: the wall between two truncated prolate ellipsoids.
//
// The geometry of problem 2 of the cardiac mechanics benchmark (Land et al. 2015,
// "Verification of cardiac mechanics software", Proc. R. Soc. A 471:20150641, §3b):
//   x = r_s sin(u) cos(v), y = r_s sin(u) sin(v), z = r_l cos(u),
// endocardium r_s = 7 mm, r_l = 17 mm; epicardium r_s = 10 mm, r_l = 20 mm; both cut by
// the base plane z = 5 mm; the apex points toward -z. Those are the defaults here.
#include "common/mesh/TetMesh.h"

#include <string>
#include <vector>

namespace fe2 {

/// A disc in the base plane: the cavity's base-cap triangles whose centroid lies in it
/// form the face set `name` (a valve ring: mitral, aortic).
struct LvBaseRing {
  std::string name;
  double x = 0.0, y = 0.0;  ///< centre in the base plane
  double radius = 0.0;
};

struct LvMeshParams {
  double endo_short = 7.0;   ///< endocardial short (equatorial) semi-axis r_s
  double endo_long = 17.0;   ///< endocardial long semi-axis r_l (along z)
  double epi_short = 10.0;   ///< epicardial short semi-axis
  double epi_long = 20.0;    ///< epicardial long semi-axis
  double base_z = 5.0;       ///< the base plane z = base_z; the apex is at z = -long
  int circumferential = 16;  ///< divisions around the long axis (>= 3)
  int longitudinal = 8;      ///< divisions from apex to base (>= 1)
  int transmural = 2;        ///< divisions from endo to epi (>= 1)
  int order = 1;             ///< 1: 4-node tets; 2: 10-node isoparametric tets
  /// > 0: the cavity is meshed too (blood), in this many layers from the long axis to
  /// the endocardium; 0: the wall only.
  int cavity_layers = 0;
  std::vector<LvBaseRing> rings;  ///< named discs of the cavity's base cap (cavity only)
};

/// Meshes the LV wall. Nodes lie on nested ellipsoidal shells whose semi-axes go
/// linearly from endo to epi in the transmural coordinate t ∈ [0, 1]; on each shell the
/// polar angle θ from the apex runs uniformly from 0 to the base plane and the
/// azimuth φ uniformly around z. The (t, φ, θ) grid cells are split into 6 tets each
/// (Kuhn split, conforming across cells and across φ = 0); at the apex the ring
/// collapses to one node per shell and the tets that would be flat are dropped (each
/// apex cell becomes a 3-tet prism), so no tet is degenerate.
///
/// Order 2 places each edge node at the image of the parameter midpoint of its edge:
/// edges on a shell get nodes on that ellipsoid, base edges on the base plane
/// (isoparametric, curved edges), not at straight-edge midpoints.
///
/// Named faces `endo`, `epi`, `base` (outward triangles, each also a node set with its
/// edge nodes); node sets `apex_endo`, `apex_epi` (the apex points). Throws InputError
/// (naming the parameter, its value and what was expected) for bad parameters.
///
/// With a cavity the grid continues inward from the endocardium: shells of semi-axes
/// (τ·r_s, r_l − (1 − τ)·d), τ from 1 (the endocardium) down to 0 (the long axis, where
/// each ring collapses to one node), each with its own apex on the axis, the last d =
/// min(r_s, (r_l − |base_z|)/2) above the endocardial apex (shells through one apex
/// would be tangent there and make slivers), so every horizontal slice of the cavity is
/// a polar grid and the base cap is flat. The same Kuhn split
/// makes the blood conform to the wall: they share the endocardium's nodes. Region 1
/// `myocardium`, region 2 `blood`; `endo` is then the interface between them (normal
/// into the blood); the cap of the cavity in the base plane is the face `base_cap`,
/// less the triangles of each ring (centroid in its disc), which form the ring's face.
TetMesh make_lv_mesh(const LvMeshParams& p);

}  // namespace fe2
