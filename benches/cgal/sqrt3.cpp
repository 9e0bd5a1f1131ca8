// CGAL sqrt(3) harness for benches/openmesh/compare_tri_schemes.sh (not part
// of the crate build or CI).
//
//   sqrt3 IN.obj LEVELS [OUT.obj]
//
// Reads a closed triangle mesh into CGAL::Surface_mesh, runs
// CGAL::Subdivision_method_3::Sqrt3_subdivision LEVELS times, and prints one
// line: "faces=<F> vertices=<V> seconds=<refinement wall time> maxrss_kib=<peak RSS>".
// Timing covers the subdivision call only (not reading or writing).
//
// CGAL 5.5's Sqrt3_mask_3 (CGAL/Subdivision_method_3/subdivision_masks_3.h) on
// a closed mesh: face point the centroid, vertex point (1 - a) p + a / n sum p_i
// with a = (4 - 2 cos(2 pi / n)) / 9 (Kobbelt), then the edge flip. Its border
// rules are not reached on closed meshes.
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/subdivision_method_3.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <sys/resource.h>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>

typedef CGAL::Simple_cartesian<double> Kernel;
typedef CGAL::Surface_mesh<Kernel::Point_3> Mesh;

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: sqrt3 IN.obj LEVELS [OUT.obj]\n";
    return 2;
  }
  Mesh mesh;
  if (!CGAL::IO::read_polygon_mesh(argv[1], mesh) || mesh.is_empty()) {
    std::cerr << "cannot read " << argv[1] << "\n";
    return 1;
  }
  if (!CGAL::is_triangle_mesh(mesh) || !CGAL::is_closed(mesh)) {
    std::cerr << argv[1] << ": not a closed triangle mesh\n";
    return 1;
  }
  int levels = std::atoi(argv[2]);
  auto t0 = std::chrono::steady_clock::now();
  CGAL::Subdivision_method_3::Sqrt3_subdivision(
      mesh, CGAL::parameters::number_of_iterations(levels));
  auto t1 = std::chrono::steady_clock::now();
  double secs = std::chrono::duration<double>(t1 - t0).count();
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  std::cout << "faces=" << mesh.number_of_faces() << " vertices=" << mesh.number_of_vertices()
            << " seconds=" << std::setprecision(6) << secs << " maxrss_kib=" << ru.ru_maxrss << "\n";
  if (argc > 3) {
    std::ofstream out(argv[3]);
    out << std::setprecision(17);
    for (auto v : mesh.vertices()) {
      const auto& p = mesh.point(v);
      out << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
    }
    for (auto f : mesh.faces()) {
      out << "f";
      for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) out << " " << (std::size_t(v) + 1);
      out << "\n";
    }
  }
  return 0;
}
