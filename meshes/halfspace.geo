// Axisymmetric elastic half-space for shtaerman, in the r-z plane (x = r, y = z, metres).
//
// The body is the quarter disc r >= 0, z <= 0, r^2 + z^2 <= domain_radius^2: the surface z = 0
// is loaded, the axis r = 0 is the symmetry axis and the arc is the far boundary (clamped by the
// solver). The mesh is fine (smallest_size) along the surface segment 0 <= r <= refined_radius
// and grows linearly with the distance d from that segment, h = smallest_size + growth * d, so
// element sizes grow geometrically layer by layer and the element count grows only with
// log(domain_radius / refined_radius).
//
// Open it in the gmsh GUI as is; shtaerman.fem.mesh overrides the parameters through ONELAB.

DefineConstant[
  refined_radius = {1, Name "Parameters/1Refined radius (m)"},
  domain_radius = {1e5, Name "Parameters/2Domain radius (m)"},
  smallest_size = {0.01, Name "Parameters/3Smallest element size (m)"},
  growth = {0.15, Name "Parameters/4Growth rate (size per distance)"},
  axis_size = {0.01, Name "Parameters/5Element size at the axis (m)"},
  axis_growth = {0.05, Name "Parameters/6Growth rate from the axis (size per distance)"},
  band_start = {1, Name "Parameters/7Start of the graded band (m)"},
  near_growth = {0.15, Name "Parameters/8Growth rate near the surface (size per distance)"},
  near_depth = {0, Name "Parameters/9Depth of the near growth (m)"},
  far_growth = {0.15, Name "Parameters/10Growth rate far away (size per distance)"},
  far_start = {1e300, Name "Parameters/11Distance where the far growth starts (m)"}
];

If (domain_radius <= refined_radius)
  Error("domain_radius (%g) must exceed refined_radius (%g)", domain_radius, refined_radius);
EndIf

Point(1) = {0, 0, 0};
Point(2) = {refined_radius, 0, 0};
Point(3) = {domain_radius, 0, 0};
Point(4) = {0, -domain_radius, 0};

Line(1) = {1, 2};       // surface, refined zone
Line(2) = {2, 3};       // surface, outer zone
Circle(3) = {3, 1, 4};  // far boundary
Line(4) = {4, 1};       // symmetry axis

Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Physical Curve("surface", 1) = {1, 2};
Physical Curve("far", 2) = {3};
Physical Curve("axis", 3) = {4};
Physical Surface("body", 4) = {1};

// Exact distance to the refined segment {0 <= x <= refined_radius, y = 0} (a Distance field
// would measure it to sample points only, leaving bumps between them).
Field[1] = MathEval;
If (band_start < refined_radius || near_depth > 0 || far_start < domain_radius)
  // The graded family of `contact --accuracy`: on the surface the size grows in proportion to
  // r beyond band_start (smallest_size * r / band_start up to the refined radius), so every
  // contact edge of the band meets the same size relative to its radius; with the distance d
  // from the segment it grows by near_growth up to near_depth, by growth beyond, and by
  // far_growth beyond far_start.
  distance = Sprintf("Sqrt(Max(x - %.17g, 0)^2 + y^2)", refined_radius);
  Field[1].F = StrCat(Sprintf("%.17g * Max(Min(x, %.17g), %.17g)", smallest_size / band_start,
                              refined_radius, band_start),
                      Sprintf(" + %.17g * ", growth), distance,
                      Sprintf(" + %.17g * Min(", near_growth - growth), distance,
                      Sprintf(", %.17g)", near_depth),
                      Sprintf(" + %.17g * Max(", far_growth - growth), distance,
                      Sprintf(" - %.17g, 0)", far_start));
Else
  Field[1].F = Sprintf("%.17g + %.17g * Sqrt(Max(x - %.17g, 0)^2 + y^2)",
                       smallest_size, growth, refined_radius);
EndIf
// Grading toward the first contact point (0, 0): the size grows from axis_size at the origin
// by axis_growth per unit distance up to smallest_size, and the field stops there (beyond it
// the segment's field alone sets the size). Every contact radius r then gets elements of about
// axis_growth * r at its edge, and the pressure cusp p(0) - p(r) ~ sqrt(r) at the axis is
// resolved. With axis_size = smallest_size the field is inactive.
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
