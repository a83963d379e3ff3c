// Axisymmetric elastic layer on a rigid base for shtaerman, in the r-z plane (x = r, y = z, m).
//
// The body is the rectangle 0 <= r <= lateral_extent, -thickness <= z <= 0: the surface z = 0 is
// loaded, the axis r = 0 is the symmetry axis, "base" is the rigid base z = -thickness and "far"
// the truncated lateral edge r = lateral_extent (clamped by the solver). The element size is
// smallest_size along the surface segment 0 <= r <= refined_radius and grows linearly with the
// distance d from it, h = smallest_size + growth * d, as in halfspace.geo, but never exceeds
// thickness_size + growth * d nor largest_size: a thin layer keeps several elements through its
// thickness at the contact, and at least thickness / largest_size everywhere.
//
// Open it in the gmsh GUI as is; shtaerman.fem.mesh overrides the parameters through ONELAB.

DefineConstant[
  refined_radius = {1, Name "Parameters/1Refined radius (m)"},
  lateral_extent = {21, Name "Parameters/2Lateral extent (m)"},
  smallest_size = {0.01, Name "Parameters/3Smallest element size (m)"},
  growth = {0.15, Name "Parameters/4Growth rate (size per distance)"},
  axis_size = {0.01, Name "Parameters/5Element size at the axis (m)"},
  axis_growth = {0.05, Name "Parameters/6Growth rate from the axis (size per distance)"},
  thickness = {1, Name "Parameters/7Layer thickness (m)"},
  thickness_size = {0.125, Name "Parameters/8Element size through the thickness (m)"},
  largest_size = {0.5, Name "Parameters/9Largest element size (m)"}
];

If (lateral_extent <= refined_radius)
  Error("lateral_extent (%g) must exceed refined_radius (%g)", lateral_extent, refined_radius);
EndIf

Point(1) = {0, 0, 0};
Point(2) = {refined_radius, 0, 0};
Point(3) = {lateral_extent, 0, 0};
Point(4) = {lateral_extent, -thickness, 0};
Point(5) = {0, -thickness, 0};

Line(1) = {1, 2};  // surface, refined zone
Line(2) = {2, 3};  // surface, outer zone
Line(3) = {3, 4};  // lateral edge (far)
Line(4) = {4, 5};  // rigid base
Line(5) = {5, 1};  // symmetry axis

Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};

Physical Curve("surface", 1) = {1, 2};
Physical Curve("far", 2) = {3};
Physical Curve("axis", 3) = {5};
Physical Curve("base", 5) = {4};
Physical Surface("body", 4) = {1};

// the size field of halfspace.geo, graded from min(smallest_size, thickness_size), capped
Field[1] = MathEval;
Field[1].F = Sprintf("Min(%.17g, %.17g + %.17g * Sqrt(Max(x - %.17g, 0)^2 + y^2))",
                     largest_size, Min(smallest_size, thickness_size), growth, refined_radius);
Field[2] = Distance;
Field[2].PointsList = {1};
Field[3] = Threshold;
Field[3].InField = 2;
Field[3].SizeMin = axis_size;
Field[3].SizeMax = smallest_size;
Field[3].DistMin = 0;
Field[3].DistMax = (smallest_size - axis_size) / axis_growth + 1e-300;
Field[3].StopAtDistMax = 1;
Field[4] = Min;
Field[4].FieldsList = {1, 3};
Background Field = 4;

Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm = 5;  // Delaunay: reproducible (Frontal-Delaunay depends on earlier meshes)
