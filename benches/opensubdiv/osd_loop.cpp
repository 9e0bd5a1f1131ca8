// OpenSubdiv (Far API) Loop harness for benches/opensubdiv/compare_loop.sh and
// benches/cgal/compare_loop.sh (not part of the crate's build or CI).
//
//   osd_loop IN.obj LEVELS [OUT.obj] [--limit]
//
// Reads a closed triangle OBJ (v / f lines only), refines it uniformly LEVELS
// times with OpenSubdiv's Loop scheme (Sdc::SCHEME_LOOP,
// Far::TopologyRefinerFactory + RefineUniform, then
// Far::PrimvarRefinerReal<double>::Interpolate level by level; with --limit,
// PrimvarRefinerReal<double>::Limit on the last level), prints one line
// "faces=<F> vertices=<V> seconds=<refinement wall time> maxrss_kib=<peak RSS>"
// and writes the last level (refined or limit positions, and its triangles)
// as OBJ. The timing covers the topology refinement and the interpolation of
// the positions (not reading, the limit or writing).
//
// OpenSubdiv 3.5's Loop rules (opensubdiv/sdc/loopScheme.h) on a closed mesh
// without creases: vertex point (1 - n beta_n) v + beta_n sum e_i with Loop's
// beta_n = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n (exactly 1/16 at n = 6),
// edge point 3/8, 3/8, 1/8, 1/8; limit mask chi_n = 1 / (n + 3 / (8 beta_n))
// per neighbour and 1 - n chi_n on the vertex (1/12 and 1/2 at n = 6).
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace OpenSubdiv;

struct V {
    double p[3];
    void Clear(void * = nullptr) { p[0] = p[1] = p[2] = 0.0; }
    void AddWithWeight(V const &s, double w) {
        for (int k = 0; k < 3; ++k) p[k] += w * s.p[k];
    }
};

static bool readObj(const char *path, std::vector<V> &pos, std::vector<int> &counts,
                    std::vector<int> &idx) {
    std::ifstream in(path);
    if (!in) return false;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream s(line);
        std::string kw;
        s >> kw;
        if (kw == "v") {
            V v;
            s >> v.p[0] >> v.p[1] >> v.p[2];
            pos.push_back(v);
        } else if (kw == "f") {
            std::string t;
            int n = 0;
            while (s >> t) {
                idx.push_back(std::stoi(t.substr(0, t.find('/'))) - 1);
                ++n;
            }
            counts.push_back(n);
        }
    }
    return true;
}

int main(int argc, char **argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s IN.obj LEVELS [OUT.obj] [--limit]\n", argv[0]);
        return 2;
    }
    int levels = std::atoi(argv[2]);
    const char *outPath = nullptr;
    bool limit = false;
    for (int a = 3; a < argc; ++a) {
        if (std::strcmp(argv[a], "--limit") == 0)
            limit = true;
        else
            outPath = argv[a];
    }
    std::vector<V> pos;
    std::vector<int> counts, idx;
    if (!readObj(argv[1], pos, counts, idx)) {
        std::fprintf(stderr, "cannot read %s\n", argv[1]);
        return 2;
    }
    for (int c : counts) {
        if (c != 3) {
            std::fprintf(stderr, "%s: not a triangle mesh\n", argv[1]);
            return 2;
        }
    }
    auto t0 = std::chrono::steady_clock::now();
    typedef Far::TopologyDescriptor Descriptor;
    Sdc::Options opts;
    opts.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    Descriptor desc;
    desc.numVertices = int(pos.size());
    desc.numFaces = int(counts.size());
    desc.numVertsPerFace = counts.data();
    desc.vertIndicesPerFace = idx.data();
    Far::TopologyRefiner *r = Far::TopologyRefinerFactory<Descriptor>::Create(
        desc, Far::TopologyRefinerFactory<Descriptor>::Options(Sdc::SCHEME_LOOP, opts));
    Far::TopologyRefiner::UniformOptions uo(levels);
    uo.fullTopologyInLastLevel = limit;  // PrimvarRefiner::Limit needs it
    r->RefineUniform(uo);
    std::vector<V> buf(r->GetNumVerticesTotal());
    std::copy(pos.begin(), pos.end(), buf.begin());
    Far::PrimvarRefinerReal<double> pr(*r);
    V *src = buf.data();
    for (int l = 1; l <= levels; ++l) {
        V *dst = src + r->GetLevel(l - 1).GetNumVertices();
        pr.Interpolate(l, src, dst);
        src = dst;
    }
    double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    Far::TopologyLevel const &last = r->GetLevel(levels);
    int nlast = last.GetNumVertices();
    std::vector<V> out(src, src + nlast);
    if (limit) {
        std::vector<V> lim(nlast);
        V *ls = out.data();
        V *ld = lim.data();
        pr.Limit(ls, ld);
        out.swap(lim);
    }
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    std::printf("faces=%d vertices=%d seconds=%.6f maxrss_kib=%ld\n", last.GetNumFaces(), nlast,
                secs, ru.ru_maxrss);
    if (outPath) {
        FILE *f = std::fopen(outPath, "w");
        if (!f) {
            std::fprintf(stderr, "cannot write %s\n", outPath);
            return 1;
        }
        for (auto const &v : out) std::fprintf(f, "v %.17g %.17g %.17g\n", v.p[0], v.p[1], v.p[2]);
        for (int fi = 0; fi < last.GetNumFaces(); ++fi) {
            Far::ConstIndexArray fv = last.GetFaceVertices(fi);
            std::fprintf(f, "f");
            for (int k = 0; k < fv.size(); ++k) std::fprintf(f, " %d", fv[k] + 1);
            std::fprintf(f, "\n");
        }
        std::fclose(f);
    }
    delete r;
    return 0;
}
