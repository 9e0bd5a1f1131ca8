// OpenMesh harness for benches/openmesh/compare_tri_schemes.sh (not part of
// the crate build or CI).
//
//   tri_schemes SCHEME IN.obj LEVELS [OUT.obj]      SCHEME: modified-butterfly | sqrt3
//
// Reads a closed triangle mesh (positions in double precision: a TriMesh with
// Vec3d points, filled by this harness's own OBJ parser, because OpenMesh's
// OBJ reader parses coordinates as float, which moves them by ~1e-8), runs OpenMesh 9.0's
// OpenMesh::Subdivider::Uniform::ModifiedButterflyT or Sqrt3T LEVELS times, and
// prints one line: "faces=<F> vertices=<V> seconds=<refinement wall time>
// maxrss_kib=<peak RSS>". Timing covers the subdivision call only.
//
// ModifiedButterFlyT.hh on a closed mesh: the 8-point butterfly (1/2, 1/8,
// -1/16) when both ends have valence 6; otherwise the stencil of each end of
// valence K != 6, the weights s_j of Zorin, Schroder and Sweldens for
// j = 0..K-1 (5/12, -1/12, -1/12 at K = 3; 3/8, 0, -1/8, 0 at K = 4) and
// 1 - sum_j s_j (3/4 up to rounding) on the vertex, averaged when both ends
// are irregular. Sqrt3T.hh: Kobbelt's alpha_n = (4 - 2 cos(2 pi / n)) / 9,
// face centroids, edge flip. Their boundary rules are not reached on closed
// meshes.
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/ModifiedButterFlyT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/Sqrt3T.hh>
#include <sys/resource.h>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

struct Traits : public OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};
typedef OpenMesh::TriMesh_ArrayKernelT<Traits> Mesh;

int main(int argc, char** argv) {
  if (argc < 4) {
    std::cerr << "usage: tri_schemes modified-butterfly|sqrt3 IN.obj LEVELS [OUT.obj]\n";
    return 2;
  }
  std::string scheme = argv[1];
  Mesh mesh;
  std::ifstream in(argv[2]);
  if (!in) {
    std::cerr << "cannot read " << argv[2] << "\n";
    return 1;
  }
  std::vector<Mesh::VertexHandle> vh;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    if (key == "v") {
      double x, y, z;
      ls >> x >> y >> z;
      vh.push_back(mesh.add_vertex(Mesh::Point(x, y, z)));
    } else if (key == "f") {
      std::vector<Mesh::VertexHandle> f;
      std::string t;
      while (ls >> t) f.push_back(vh.at(std::stoi(t.substr(0, t.find('/'))) - 1));
      if (!mesh.add_face(f).is_valid()) {
        std::cerr << argv[2] << ": face rejected\n";
        return 1;
      }
    }
  }
  int levels = std::atoi(argv[3]);
  auto t0 = std::chrono::steady_clock::now();
  bool ok = false;
  if (scheme == "modified-butterfly") {
    OpenMesh::Subdivider::Uniform::ModifiedButterflyT<Mesh, double> sub;
    sub.attach(mesh);
    ok = sub(levels);
    sub.detach();
  } else if (scheme == "sqrt3") {
    OpenMesh::Subdivider::Uniform::Sqrt3T<Mesh, double> sub;
    sub.attach(mesh);
    ok = sub(levels);
    sub.detach();
  } else {
    std::cerr << "unknown scheme " << scheme << "\n";
    return 2;
  }
  auto t1 = std::chrono::steady_clock::now();
  if (!ok) {
    std::cerr << "subdivision failed\n";
    return 1;
  }
  double secs = std::chrono::duration<double>(t1 - t0).count();
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  std::cout << "faces=" << mesh.n_faces() << " vertices=" << mesh.n_vertices()
            << " seconds=" << std::setprecision(6) << secs << " maxrss_kib=" << ru.ru_maxrss << "\n";
  if (argc > 4) {
    std::ofstream out(argv[4]);
    out << std::setprecision(17);
    for (auto v : mesh.vertices()) {
      const auto& p = mesh.point(v);
      out << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
    }
    for (auto f : mesh.faces()) {
      out << "f";
      for (auto v : mesh.fv_ccw_range(f)) out << " " << (v.idx() + 1);
      out << "\n";
    }
  }
  return 0;
}
