// Writes tests/data/floors/bumps.brep: a cubic B-spline face over [0, 100] x [0, 75]
// with several bumps, the sculptured floor of the CLI tests and of the depth
// benchmark. Built as `make_brep_floor`; run once, the output is committed.
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepTools.hxx>
#include <GeomAPI_PointsToBSplineSurface.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <cmath>
#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_brep_floor OUT.brep\n";
    return 2;
  }
  auto z = [](double x, double y) {
    return -20 + 3 * std::exp(-((x - 30) * (x - 30) + (y - 40) * (y - 40)) / 60.0) +
           2 * std::exp(-((x - 70) * (x - 70) + (y - 55) * (y - 55)) / 40.0) +
           1.5 * std::exp(-((x - 60) * (x - 60) + (y - 15) * (y - 15)) / 90.0) + 0.02 * x - 0.01 * y +
           0.5 * std::sin(0.15 * x) * std::cos(0.1 * y);
  };
  TColgp_Array2OfPnt pts(1, 41, 1, 31);
  for (int i = 1; i <= 41; ++i)
    for (int j = 1; j <= 31; ++j) pts.SetValue(i, j, gp_Pnt(2.5 * (i - 1), 2.5 * (j - 1), z(2.5 * (i - 1), 2.5 * (j - 1))));
  GeomAPI_PointsToBSplineSurface fit(pts, 3, 3, GeomAbs_C2, 1e-4);
  if (!BRepTools::Write(BRepBuilderAPI_MakeFace(fit.Surface(), 1e-7), argv[1])) return 1;
  return 0;
}
