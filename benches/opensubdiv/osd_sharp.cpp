// OpenSubdiv (Far API) reference for `subdiv-lab subdivide` on open meshes
// with crease and corner tags. Not part of the crate's build.
//
// Usage: osd_sharp catmark|loop none|edge-only|edge-and-corner uniform|chaikin
//                  LEVELS IN.obj TAGS|- OUT.obj [--time|--limit]
//
// Reads the OBJ's v and f lines and the `t crease NI/NF/0 ...` and
// `t corner NI/NF/0 ...` lines of the OBJ and of TAGS (a file of t lines, or
// "-" for none), builds a Far::TopologyRefiner from a TopologyDescriptor with
// those sharpness values, refines uniformly LEVELS times and interpolates the
// positions with Far::PrimvarRefinerReal<double>. Writes the last level as
// OBJ: every vertex, and every face that is not a hole; with --limit the
// vertices are the limit positions of the last level's vertices
// (PrimvarRefinerReal<double>::Limit). With --time it also
// prints the best of 3 wall times of (topology + refinement + interpolation)
// to standard error.
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>

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

struct Input {
    std::vector<V> pos;
    std::vector<int> counts, idx;
    std::vector<int> creasePairs, corners;
    std::vector<float> creaseW, cornerW;
};

static void parseTag(std::istringstream &s, Input &in) {
    std::string name, counts;
    s >> name >> counts;
    int ni = 0, nf = 0, ns = 0;
    std::sscanf(counts.c_str(), "%d/%d/%d", &ni, &nf, &ns);
    std::vector<int> ints(ni);
    std::vector<float> floats(nf);
    for (int i = 0; i < ni; ++i) s >> ints[i];
    for (int i = 0; i < nf; ++i) s >> floats[i];
    if (name == "crease") {
        for (int k = 0; 2 * k + 1 < ni; ++k) {
            in.creasePairs.push_back(ints[2 * k]);
            in.creasePairs.push_back(ints[2 * k + 1]);
            in.creaseW.push_back(nf == 1 ? floats[0] : floats[k]);
        }
    } else if (name == "corner") {
        for (int k = 0; k < ni; ++k) {
            in.corners.push_back(ints[k]);
            in.cornerW.push_back(nf == 1 ? floats[0] : floats[k]);
        }
    }
}

static bool read(const char *path, Input &in, bool tagsOnly) {
    std::ifstream f(path);
    if (!f) return false;
    std::string line;
    while (std::getline(f, line)) {
        std::istringstream s(line);
        std::string kw;
        s >> kw;
        if (kw == "t") {
            parseTag(s, in);
        } else if (tagsOnly) {
            continue;
        } else if (kw == "v") {
            V v;
            s >> v.p[0] >> v.p[1] >> v.p[2];
            in.pos.push_back(v);
        } else if (kw == "f") {
            std::string t;
            int n = 0;
            while (s >> t) {
                in.idx.push_back(std::stoi(t.substr(0, t.find('/'))) - 1);
                ++n;
            }
            in.counts.push_back(n);
        }
    }
    return true;
}

static Far::TopologyRefiner *build(Input const &in, Sdc::SchemeType type, Sdc::Options opt,
                                   int levels) {
    Far::TopologyDescriptor d;
    d.numVertices = (int)in.pos.size();
    d.numFaces = (int)in.counts.size();
    d.numVertsPerFace = in.counts.data();
    d.vertIndicesPerFace = in.idx.data();
    d.numCreases = (int)in.creaseW.size();
    d.creaseVertexIndexPairs = in.creasePairs.data();
    d.creaseWeights = in.creaseW.data();
    d.numCorners = (int)in.cornerW.size();
    d.cornerVertexIndices = in.corners.data();
    d.cornerWeights = in.cornerW.data();
    Far::TopologyRefiner *r = Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Create(
        d, Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Options(type, opt));
    if (!r) return nullptr;
    Far::TopologyRefiner::UniformOptions u(levels);
    u.fullTopologyInLastLevel = true;
    r->RefineUniform(u);
    return r;
}

static std::vector<V> interpolate(Far::TopologyRefiner const &r, Input const &in) {
    std::vector<V> buf(r.GetNumVerticesTotal());
    for (size_t i = 0; i < in.pos.size(); ++i) buf[i] = in.pos[i];
    Far::PrimvarRefinerReal<double> pr(r);
    V *src = buf.data();
    for (int l = 1; l <= r.GetMaxLevel(); ++l) {
        V *dst = src + r.GetLevel(l - 1).GetNumVertices();
        pr.Interpolate(l, src, dst);
        src = dst;
    }
    return buf;
}

int main(int argc, char **argv) {
    if (argc < 8) {
        std::fprintf(stderr,
                     "usage: %s catmark|loop none|edge-only|edge-and-corner uniform|chaikin "
                     "LEVELS IN.obj TAGS|- OUT.obj [--time]\n",
                     argv[0]);
        return 2;
    }
    Sdc::SchemeType type = std::strcmp(argv[1], "loop") == 0 ? Sdc::SCHEME_LOOP : Sdc::SCHEME_CATMARK;
    Sdc::Options opt;
    if (std::strcmp(argv[2], "none") == 0)
        opt.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_NONE);
    else if (std::strcmp(argv[2], "edge-only") == 0)
        opt.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    else
        opt.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
    opt.SetCreasingMethod(std::strcmp(argv[3], "chaikin") == 0 ? Sdc::Options::CREASE_CHAIKIN
                                                               : Sdc::Options::CREASE_UNIFORM);
    int levels = std::atoi(argv[4]);
    Input in;
    if (!read(argv[5], in, false)) {
        std::fprintf(stderr, "cannot read %s\n", argv[5]);
        return 1;
    }
    if (std::strcmp(argv[6], "-") != 0 && !read(argv[6], in, true)) {
        std::fprintf(stderr, "cannot read %s\n", argv[6]);
        return 1;
    }
    bool timing = argc > 8 && std::strcmp(argv[8], "--time") == 0;
    bool limit = argc > 8 && std::strcmp(argv[8], "--limit") == 0;
    if (timing) {
        double best = 1e300;
        for (int run = 0; run < 3; ++run) {
            auto t0 = std::chrono::steady_clock::now();
            Far::TopologyRefiner *r = build(in, type, opt, levels);
            std::vector<V> buf = interpolate(*r, in);
            auto t1 = std::chrono::steady_clock::now();
            double s = std::chrono::duration<double>(t1 - t0).count();
            if (s < best) best = s;
            std::fprintf(stderr, "opensubdiv run %d: %.3f s (%d faces)\n", run + 1, s,
                         r->GetLevel(levels).GetNumFaces());
            delete r;
        }
        std::fprintf(stderr, "opensubdiv best of 3: %.3f s\n", best);
    }
    Far::TopologyRefiner *r = build(in, type, opt, levels);
    if (!r) {
        std::fprintf(stderr, "OpenSubdiv refused the mesh\n");
        return 1;
    }
    std::vector<V> buf = interpolate(*r, in);
    Far::TopologyLevel const &last = r->GetLevel(levels);
    size_t first = buf.size() - last.GetNumVertices();
    if (limit) {
        std::vector<V> lim(last.GetNumVertices());
        V const *src = buf.data() + first;
        V *dst = lim.data();
        Far::PrimvarRefinerReal<double>(*r).Limit(src, dst);
        for (size_t i = 0; i < lim.size(); ++i) buf[first + i] = lim[i];
    }
    std::FILE *out = std::fopen(argv[7], "w");
    if (!out) return 1;
    for (int i = 0; i < last.GetNumVertices(); ++i) {
        V const &v = buf[first + i];
        std::fprintf(out, "v %.17g %.17g %.17g\n", v.p[0], v.p[1], v.p[2]);
    }
    for (int f = 0; f < last.GetNumFaces(); ++f) {
        if (last.IsFaceHole(f)) continue;
        Far::ConstIndexArray fv = last.GetFaceVertices(f);
        std::fprintf(out, "f");
        for (int k = 0; k < fv.size(); ++k) std::fprintf(out, " %d", fv[k] + 1);
        std::fprintf(out, "\n");
    }
    std::fclose(out);
    delete r;
    return 0;
}
