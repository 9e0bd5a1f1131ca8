// OpenSubdiv (Far API) oracle for `subdiv-lab subdivide --scheme catmull-clark`.
//
// Usage: osd_refine IN.obj LEVELS OURS.obj [--limit]
//
// Reads a closed polygon OBJ (v / f lines only), refines it uniformly LEVELS
// times with OpenSubdiv's Catmull-Clark (Far::TopologyRefiner,
// Far::PrimvarRefinerReal<double>::Interpolate; with --limit, ::Limit on the
// last level), reads our refined OBJ, and prints the largest distance between
// each OpenSubdiv vertex and the nearest of ours and vice versa (the vertex
// orders differ: OpenSubdiv puts face points first). Brute force O(N^2): meant
// for the small shipped meshes.
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
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

static double maxNearest(const std::vector<V> &a, const std::vector<V> &b) {
    double worst = 0.0;
    for (auto const &x : a) {
        double best = INFINITY;
        for (auto const &y : b) {
            double d = std::sqrt(std::pow(x.p[0] - y.p[0], 2) + std::pow(x.p[1] - y.p[1], 2) +
                                 std::pow(x.p[2] - y.p[2], 2));
            best = std::min(best, d);
        }
        worst = std::max(worst, best);
    }
    return worst;
}

int main(int argc, char **argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: %s IN.obj LEVELS OURS.obj [--limit]\n", argv[0]);
        return 2;
    }
    int levels = std::atoi(argv[2]);
    bool limit = argc > 4 && std::strcmp(argv[4], "--limit") == 0;
    std::vector<V> pos, ours;
    std::vector<int> counts, idx, c2, i2;
    if (!readObj(argv[1], pos, counts, idx) || !readObj(argv[3], ours, c2, i2)) {
        std::fprintf(stderr, "cannot read input\n");
        return 2;
    }
    typedef Far::TopologyDescriptor Descriptor;
    Sdc::Options opts;
    opts.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    Descriptor desc;
    desc.numVertices = int(pos.size());
    desc.numFaces = int(counts.size());
    desc.numVertsPerFace = counts.data();
    desc.vertIndicesPerFace = idx.data();
    Far::TopologyRefiner *r = Far::TopologyRefinerFactory<Descriptor>::Create(
        desc, Far::TopologyRefinerFactory<Descriptor>::Options(Sdc::SCHEME_CATMARK, opts));
    Far::TopologyRefiner::UniformOptions uo(levels);
    uo.fullTopologyInLastLevel = true;  // needed by PrimvarRefiner::Limit
    r->RefineUniform(uo);
    std::vector<V> buf(r->GetNumVerticesTotal());
    std::copy(pos.begin(), pos.end(), buf.begin());
    // Double-precision weights (PrimvarRefinerReal<double>, OpenSubdiv >= 3.5).
    Far::PrimvarRefinerReal<double> pr(*r);
    V *src = buf.data();
    for (int l = 1; l <= levels; ++l) {
        V *dst = src + r->GetLevel(l - 1).GetNumVertices();
        pr.Interpolate(l, src, dst);
        src = dst;
    }
    int nlast = r->GetLevel(levels).GetNumVertices();
    std::vector<V> last(src, src + nlast);
    if (limit) {
        std::vector<V> lim(nlast);
        V *ls = last.data();
        V *ld = lim.data();
        pr.Limit(ls, ld);
        last = lim;
    }
    std::printf("%s levels=%d %s vertices osd=%d ours=%zu max_dist osd->ours=%.3e ours->osd=%.3e\n",
                argv[1], levels, limit ? "limit" : "refined", nlast, ours.size(),
                maxNearest(last, ours), maxNearest(ours, last));
    delete r;
    return 0;
}
