#!/usr/bin/env python3
"""Import loops between the source files and the top-level modules of the crate
(stdlib only).

Builds the file-level dependency graph of src/**/*.rs and, from it, the graph of
the top-level modules (`spectral`, `scheme`, ...; the binary's modules are
`bin:cli` etc.). Prints the strongly connected components of more than one
file, the strongly connected components of more than one top-level module and
the two-way pairs of top-level modules (`a <-> b`: a file of `a` uses `b` and a
file of `b` uses `a`); exits 1 if there is any of them.

Edges: a file depends on the file that defines the module a path names, for
every path in it (in `use` trees, groups expanded, and in expressions and
types) that starts with `crate::`, `super::`, `self::`, the name of a child
module of the module it is written in (`pub use child::X`, `child::f()`),
or a name a `use` in the same module bound to a module (`use
crate::spectral::kernel;` then `kernel::BATCH`); `subdiv_lab::...` in the
binary's files counts as the library's `crate::...`. The module a path names
is its longest prefix that is a module (so `crate::spectral::kernel::BATCH`
names `spectral::kernel`, defined by src/spectral/kernel/mod.rs); a directory
module's mod.rs stands for the module. A path to an item that a module
re-exports (`pub use`) names the file that defines the item. `mod child;`
itself is not an edge. Comments, strings and character literals are ignored,
so doc links are not dependencies. Inline modules (`mod tests { ... }`)
belong to their file, but paths inside them are resolved from the inline
module.

Usage: .ci/import_cycles.py [--ignore PREFIX]... [--root DIR] [--edges] [--known FILE]
  --ignore PREFIX  drop the files whose path (relative to the root, e.g.
                   src/sweep/) starts with PREFIX, with their edges
  --root DIR       the crate root (default: the parent of this script's
                   directory)
  --edges          also print the edges inside each component and the file
                   edges behind each two-way module pair
  --known FILE     loops and pairs that are known and still to be removed, one
                   a line: `files A B ...` (a file loop, its members),
                   `modules a b ...` (a module loop), `pair a b`; `#` starts a
                   comment. Exits 1 on a loop or pair not listed and on a listed
                   one that no longer occurs (the list can only shrink).
"""

import argparse
import os
import re
import sys

IDENT = r"[A-Za-z_][A-Za-z0-9_]*"


def strip_code(text):
    """The text with comments, string and char literals blanked (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if text.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif text.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "r" and re.match(r'r#*"', text[i:]) and not re.match(r"[A-Za-z0-9_]", text[i - 1 : i] or " "):
            m = re.match(r'r(#*)"', text[i:])
            end = '"' + m.group(1)
            j = text.find(end, i + len(m.group(0)))
            j = n if j < 0 else j + len(end)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "'":
            # char literal ('a', '\n', '\u{..}') or a lifetime ('a)
            m = re.match(r"'(\\.[^']*|[^\\'])'", text[i:])
            if m:
                out.append(" " * len(m.group(0)))
                i += len(m.group(0))
            else:
                out.append(c)
                i += 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def expand_use_tree(tree):
    """`a::{b, c::{d, self}}` -> [['a','b'], ['a','c','d'], ['a','c']]."""
    tree = re.sub(r"\s+", "", tree)
    if tree.startswith("::"):
        tree = tree[2:]

    def split_top(s):
        parts, depth, cur = [], 0, ""
        for ch in s:
            if ch == "{":
                depth += 1
            elif ch == "}":
                depth -= 1
            if ch == "," and depth == 0:
                parts.append(cur)
                cur = ""
            else:
                cur += ch
        if cur:
            parts.append(cur)
        return parts

    def rec(s):
        if s.startswith("::"):
            s = s[2:]
        brace = s.find("{")
        if brace < 0:
            # (`X as Y` renames are removed by the caller, before whitespace goes.)
            segs = [x for x in s.split("::") if x]
            if segs and segs[-1] == "self":
                segs = segs[:-1]
            return [segs]
        prefix = [x for x in s[:brace].split("::") if x]
        inner = s[brace + 1 : s.rfind("}")]
        out = []
        for part in split_top(inner):
            for p in rec(part):
                out.append(prefix + p)
        if not inner.strip():
            out.append(prefix)
        return out

    return rec(tree)


class Crate:
    def __init__(self, root):
        self.root = root
        # module path tuple -> file (relative), per crate ("lib", "bin")
        self.modules = {"lib": {}, "bin": {}}
        self.files = {}  # file -> (crate, module path tuple)
        self._reexports = {}
        for crate, top in (("lib", "src/lib.rs"), ("bin", "src/main.rs")):
            if os.path.exists(os.path.join(root, top)):
                self.walk(crate, top, ())

    def read(self, rel):
        with open(os.path.join(self.root, rel), encoding="utf-8") as f:
            return f.read()

    def walk(self, crate, rel, modpath):
        if rel in self.files:
            return
        self.modules[crate][modpath] = rel
        self.files[rel] = (crate, modpath)
        text = strip_code(self.read(rel))
        base = os.path.basename(rel)
        d = os.path.dirname(rel)
        if base not in ("lib.rs", "main.rs", "mod.rs"):
            d = os.path.join(d, base[:-3])
        # `mod name;` at any depth of inline modules: `mod a { mod b; }` puts b in a/
        for inline, name in self.mod_decls(text):
            sub = os.path.join(d, *inline)
            for cand in (os.path.join(sub, name + ".rs"), os.path.join(sub, name, "mod.rs")):
                if os.path.exists(os.path.join(self.root, cand)):
                    self.walk(crate, os.path.normpath(cand), modpath + tuple(inline) + (name,))
                    break

    @staticmethod
    def inline_scopes(text):
        """[(start, end, inline module names)] of the inline modules of a file."""
        scopes = []
        stack = []  # (name or None, start)
        for m in re.finditer(r"\bmod\s+(" + IDENT + r")\s*\{|[{}]", text):
            tok = m.group(0)
            if m.group(1):
                stack.append((m.group(1), m.end()))
            elif tok == "{":
                stack.append((None, m.end()))
            elif stack:
                name, start = stack.pop()
                if name is not None:
                    names = [s[0] for s in stack if s[0] is not None] + [name]
                    scopes.append((start, m.start(), names))
        return scopes

    def mod_decls(self, text):
        scopes = self.inline_scopes(text)
        for m in re.finditer(r"\bmod\s+(" + IDENT + r")\s*;", text):
            inline = []
            for start, end, names in scopes:
                if start <= m.start() < end and len(names) > len(inline):
                    inline = names
            yield inline, m.group(1)

    def resolve(self, crate, modpath, segs, depth=0):
        """The file of the longest module prefix of an absolute path; when the
        path goes on to an item that this module re-exports (`pub use`), the
        file of the re-exported path instead (`crate::Error` -> src/error.rs)."""
        mods = self.modules[crate]
        for k in range(len(segs), -1, -1):
            if tuple(segs[:k]) in mods:
                f = mods[tuple(segs[:k])]
                if k < len(segs) and depth < 8:
                    target = self.reexports(f).get(segs[k])
                    if target is not None:
                        return self.resolve(crate, (), target + segs[k + 1 :], depth + 1) or f
                return f
        return None

    def reexports(self, rel):
        """{name: absolute path} of the `pub use` items of a file (globs and
        external crates left out)."""
        if rel in self._reexports:
            return self._reexports[rel]
        crate, modpath = self.files[rel]
        text = strip_code(self.read(rel))
        out = {}
        for m in re.finditer(r"\bpub(?:\s*\([^)]*\))?\s+use\s+([^;]*);", text):
            tree = re.sub(r"\s+as\s+(" + IDENT + ")", r"@\1", m.group(1))
            for segs in expand_use_tree(tree):
                if not segs or segs[-1] == "*":
                    continue
                name = segs[-1].split("@")[-1]
                segs = segs[:-1] + [segs[-1].split("@")[0]]
                absolute = self.absolute(crate, modpath, segs)
                if absolute is not None:
                    out[name] = absolute
        self._reexports[rel] = out
        return out

    def absolute(self, crate, here, segs):
        """The absolute module path of a use path written in module `here`, or
        None for an external crate."""
        if segs[0] == "crate":
            return segs[1:]
        if segs[0] in ("super", "self"):
            base, k = list(here), 0
            while k < len(segs) and segs[k] in ("super", "self"):
                if segs[k] == "super":
                    base = base[:-1]
                k += 1
            return base + segs[k:]
        if tuple(here) + (segs[0],) in self.modules[crate]:
            return list(here) + segs
        return None

    def target(self, crate, here, segs, aliases):
        """(crate, absolute path) of a path written in module `here`, or None
        for a path into an external crate or to a local item (a variable, a
        type's associated item)."""
        first = segs[0]
        if first == "crate":
            return crate, segs[1:]
        if first == "subdiv_lab" and crate == "bin":
            return "lib", segs[1:]
        if first in ("super", "self"):
            base, k = list(here), 0
            while k < len(segs) and segs[k] in ("super", "self"):
                if segs[k] == "super":
                    base = base[:-1]
                k += 1
            return crate, base + segs[k:]
        if tuple(here) + (first,) in self.modules[crate]:
            return crate, list(here) + segs
        bound = aliases.get(tuple(here), {}).get(first)
        if bound is not None:
            return bound[0], bound[1] + segs[1:]
        return None

    def deps(self, rel):
        crate, modpath = self.files[rel]
        text = strip_code(self.read(rel))
        scopes = self.inline_scopes(text)

        def scope_at(pos):
            best = []
            for start, end, names in scopes:
                if start <= pos < end and len(names) > len(best):
                    best = names
            return modpath + tuple(best)

        paths = []  # (position, segments)
        used = []
        aliases = {}  # module path -> {name: (crate, absolute module path)}
        for m in re.finditer(r"\buse\s+([^;]*);", text):
            used.append((m.start(), m.end()))
            here = scope_at(m.start())
            tree = re.sub(r"\s+as\s+(" + IDENT + ")", r"@\1", m.group(1))
            for segs in expand_use_tree(tree):
                if not segs:
                    continue
                name = segs[-1].split("@")[-1]
                segs = segs[:-1] + [segs[-1].split("@")[0]]
                paths.append((m.start(), segs))
                t = self.target(crate, here, segs, aliases)
                if t is not None and name not in ("*", "self", "_") and tuple(t[1]) in self.modules[t[0]]:
                    aliases.setdefault(tuple(here), {})[name] = t
        # A path in an expression or a type: an identifier not preceded by
        # `::` (nor part of a longer identifier), followed by `::ident`s.
        for m in re.finditer(r"(?<![:\w])(" + IDENT + r")((?:\s*::\s*" + IDENT + r")+)", text):
            if any(s <= m.start() < e for s, e in used):
                continue
            if text[: m.start()].rstrip().endswith("::"):
                continue
            segs = [m.group(1)] + re.findall(IDENT, m.group(2))
            paths.append((m.start(), segs))
        out = set()
        for pos, segs in paths:
            t = self.target(crate, scope_at(pos), segs, aliases)
            if t is None:
                continue
            f = self.resolve(t[0], (), t[1])
            if f and f != rel:
                out.add(f)
        return out

    def top_module(self, rel):
        """The top-level module a file belongs to: `spectral` for
        src/spectral/kernel/mod.rs, `crate` for src/lib.rs, `bin:cli` for a
        file of the binary's `cli` module, `bin` for src/main.rs."""
        crate, modpath = self.files[rel]
        if crate == "lib":
            return modpath[0] if modpath else "crate"
        return "bin:" + modpath[0] if modpath else "bin"


def sccs(graph):
    """Tarjan's strongly connected components (iterative)."""
    index, low, on, stack, out = {}, {}, set(), [], []
    counter = [0]
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = counter[0]
        counter[0] += 1
        stack.append(root)
        on.add(root)
        while work:
            v, it = work[-1]
            nxt = next(it, None)
            if nxt is None:
                work.pop()
                if work:
                    u = work[-1][0]
                    low[u] = min(low[u], low[v])
                if low[v] == index[v]:
                    comp = []
                    while True:
                        w = stack.pop()
                        on.discard(w)
                        comp.append(w)
                        if w == v:
                            break
                    out.append(sorted(comp))
            elif nxt not in index:
                index[nxt] = low[nxt] = counter[0]
                counter[0] += 1
                stack.append(nxt)
                on.add(nxt)
                work.append((nxt, iter(sorted(graph[nxt]))))
            elif nxt in on:
                low[v] = min(low[v], index[nxt])
    return out


def analyse(root, ignore=()):
    """The file graph, its loops, the top-level module graph, its loops and
    its two-way pairs (with the file edges behind each direction)."""
    crate = Crate(root)
    keep = [f for f in crate.files if not any(f.startswith(p) for p in ignore)]
    keep_set = set(keep)
    graph = {f: {d for d in crate.deps(f) if d in keep_set} for f in keep}
    loops = sorted((c for c in sccs(graph) if len(c) > 1), key=lambda c: (-len(c), c))
    modgraph, behind = {}, {}
    for f in keep:
        modgraph.setdefault(crate.top_module(f), set())
    for f, ds in graph.items():
        a = crate.top_module(f)
        for d in ds:
            b = crate.top_module(d)
            if a != b:
                modgraph[a].add(b)
                behind.setdefault((a, b), []).append((f, d))
    mod_loops = sorted((c for c in sccs(modgraph) if len(c) > 1), key=lambda c: (-len(c), c))
    pairs = sorted((a, b) for a in modgraph for b in modgraph[a] if a < b and a in modgraph[b])
    return {
        "graph": graph,
        "loops": loops,
        "modgraph": modgraph,
        "mod_loops": mod_loops,
        "pairs": pairs,
        "behind": {k: sorted(v) for k, v in behind.items()},
    }


def read_known(path):
    """The set of findings listed in a --known file."""
    known = set()
    with open(path, encoding="utf-8") as f:
        for line in f:
            words = line.split("#", 1)[0].split()
            if not words:
                continue
            if words[0] not in ("files", "modules", "pair") or len(words) < 3:
                raise SystemExit(f"{path}: cannot read line: {line.strip()}")
            known.add((words[0], tuple(sorted(words[1:]))))
    return known


def findings(r):
    """The loops and pairs of an analysis as `--known` entries."""
    out = [("files", tuple(c)) for c in r["loops"]]
    out += [("modules", tuple(c)) for c in r["mod_loops"]]
    out += [("pair", p) for p in r["pairs"]]
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--ignore", action="append", default=[], metavar="PREFIX")
    ap.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ap.add_argument("--edges", action="store_true")
    ap.add_argument("--known", metavar="FILE")
    args = ap.parse_args(argv)
    known = read_known(args.known) if args.known else set()
    r = analyse(args.root, args.ignore)
    graph, loops = r["graph"], r["loops"]
    edges = sum(len(v) for v in graph.values())
    medges = sum(len(v) for v in r["modgraph"].values())
    print(f"{len(graph)} files, {edges} edges, {len(loops)} import loop(s) between files")
    print(
        f"{len(r['modgraph'])} top-level modules, {medges} edges, "
        f"{len(r['mod_loops'])} import loop(s) between modules, {len(r['pairs'])} two-way pair(s)"
    )
    def tag(kind, members):
        return " (known)" if (kind, tuple(sorted(members))) in known else ""

    for c in loops:
        print(f"\nloop of {len(c)} files{tag('files', c)}:")
        members = set(c)
        for f in c:
            print(f"  {f}")
            if args.edges:
                for d in sorted(graph[f] & members):
                    print(f"      -> {d}")
    for c in r["mod_loops"]:
        print(f"\nloop of {len(c)} top-level modules{tag('modules', c)}: {' '.join(c)}")
    for a, b in r["pairs"]:
        print(f"\ntwo-way pair{tag('pair', (a, b))}: {a} <-> {b}")
        if args.edges:
            for x, y in ((a, b), (b, a)):
                for f, d in r["behind"][(x, y)]:
                    print(f"  {f} -> {d}")
    found = {(k, tuple(sorted(m))) for k, m in findings(r)}
    new = found - known
    stale = sorted(known - found)
    for kind, members in stale:
        print(f"\nlisted in {args.known} but no longer found (remove the line): {kind} {' '.join(members)}")
    if args.known:
        print(f"\n{len(new)} new, {len(found & known)} known, {len(stale)} no longer found")
    return 1 if new or stale else 0


if __name__ == "__main__":
    sys.exit(main())
