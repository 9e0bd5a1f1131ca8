#!/usr/bin/env python3
"""Tests of .ci/import_cycles.py on tiny crates written to a temporary directory.

Run: python3 .ci/test_import_cycles.py (stdlib only; .ci/run runs it).
"""

import contextlib
import importlib.util
import io
import os
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location("import_cycles", os.path.join(HERE, "import_cycles.py"))
ic = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(ic)


def crate(files):
    """A temporary crate root holding `files` ({relative path: text})."""
    tmp = tempfile.TemporaryDirectory()
    for rel, text in files.items():
        path = os.path.join(tmp.name, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
    return tmp


def run(files, known=None):
    """(analysis, exit status of the command line) for a crate; `known`: the
    text of a --known file."""
    with crate(files) as root:
        result = ic.analyse(root)
        args = ["--root", root]
        if known is not None:
            path = os.path.join(root, "known")
            with open(path, "w", encoding="utf-8") as f:
                f.write(known)
            args += ["--known", path]
        with contextlib.redirect_stdout(io.StringIO()):
            status = ic.main(args)
    return result, status


# A parent that re-exports from its child while the child uses the parent:
# the only edge from the parent is the `pub use child::...` line.
PARENT_CHILD_LOOP = {
    "src/lib.rs": "pub mod a;\n",
    "src/a/mod.rs": "mod child;\npub use child::Thing;\npub struct Base;\n",
    "src/a/child.rs": "use super::Base;\npub struct Thing(pub Base);\n",
}

# The parent's only edge to the child is a call in an expression.
PARENT_CALLS_CHILD = {
    "src/lib.rs": "pub mod a;\n",
    "src/a/mod.rs": "mod child;\npub struct Base;\npub fn run() { child::f() }\n",
    "src/a/child.rs": "pub fn f() { let _ = super::Base; }\n",
}

# The parent's only edge to the child goes through `self::`.
PARENT_SELF_CHILD = {
    "src/lib.rs": "pub mod a;\n",
    "src/a/mod.rs": "mod child;\npub struct Base;\npub fn run() { self::child::f() }\n",
    "src/a/child.rs": "pub fn f() { let _ = crate::a::Base; }\n",
}

# No file loop, but `x` uses `y` and `y` uses `x`.
TWO_WAY_PAIR = {
    "src/lib.rs": "pub mod x;\npub mod y;\n",
    "src/x/mod.rs": "pub mod a;\npub mod d;\n",
    "src/x/a.rs": "use crate::y::b::B;\npub struct A(pub B);\n",
    "src/x/d.rs": "pub struct D;\n",
    "src/y/mod.rs": "pub mod b;\npub mod c;\n",
    "src/y/b.rs": "pub struct B;\n",
    "src/y/c.rs": "pub fn f() -> crate::x::d::D { crate::x::d::D }\n",
}

# Three modules in a ring, no two of them both ways, and no file loop.
MODULE_RING = {
    "src/lib.rs": "pub mod p;\npub mod q;\npub mod r;\n",
    "src/p/mod.rs": "pub mod a;\npub mod f;\n",
    "src/p/a.rs": "pub struct A(pub crate::q::b::B);\n",
    "src/p/f.rs": "pub struct F;\n",
    "src/q/mod.rs": "pub mod b;\npub mod c;\n",
    "src/q/b.rs": "pub struct B;\n",
    "src/q/c.rs": "pub struct C(pub crate::r::d::D);\n",
    "src/r/mod.rs": "pub mod d;\npub mod e;\n",
    "src/r/d.rs": "pub struct D;\n",
    "src/r/e.rs": "pub fn f(_: &crate::p::f::F) {}\n",
}

# Layered: rules below analyses below a front end; parents re-export their
# children, children use their siblings and the layers below only; a
# re-exported name reached through the parent names the child that defines it.
LAYERED = {
    "src/lib.rs": "pub mod rules;\npub mod analysis;\npub use rules::Rule;\n",
    "src/rules/mod.rs": "mod rule;\nmod table;\npub use rule::Rule;\npub use table::TABLE;\n",
    "src/rules/rule.rs": "pub struct Rule;\n",
    "src/rules/table.rs": "use super::Rule;\npub const TABLE: [u8; 1] = [0];\npub fn r() -> Rule { Rule }\n",
    "src/analysis/mod.rs": "mod run;\npub use run::run;\n",
    "src/analysis/run.rs": (
        "use crate::rules::{self, Rule};\n"
        "// a comment naming super::super::analysis is not an edge\n"
        'pub fn run() -> Rule { let _ = "crate::analysis"; let _ = rules::TABLE; Rule }\n'
    ),
    "src/main.rs": "mod cli;\nfn main() { cli::go() }\n",
    "src/cli/mod.rs": "mod args;\npub fn go() { args::parse(); subdiv_lab::analysis::run(); }\n",
    "src/cli/args.rs": "pub fn parse() {}\n",
}


class ImportCycles(unittest.TestCase):
    def assert_loop(self, files, members):
        result, status = run(files)
        self.assertIn(sorted(members), result["loops"])
        self.assertEqual(status, 1)

    def test_parent_reexport_of_child_closes_a_loop(self):
        self.assert_loop(PARENT_CHILD_LOOP, ["src/a/mod.rs", "src/a/child.rs"])

    def test_parent_call_into_child_closes_a_loop(self):
        self.assert_loop(PARENT_CALLS_CHILD, ["src/a/mod.rs", "src/a/child.rs"])

    def test_parent_self_path_into_child_closes_a_loop(self):
        self.assert_loop(PARENT_SELF_CHILD, ["src/a/mod.rs", "src/a/child.rs"])

    def test_two_way_module_pair_without_file_loop(self):
        result, status = run(TWO_WAY_PAIR)
        self.assertEqual(result["loops"], [])
        self.assertEqual(result["pairs"], [("x", "y")])
        self.assertEqual(result["behind"][("x", "y")], [("src/x/a.rs", "src/y/b.rs")])
        self.assertEqual(result["behind"][("y", "x")], [("src/y/c.rs", "src/x/d.rs")])
        self.assertEqual(status, 1)

    def test_module_ring_without_two_way_pair(self):
        result, status = run(MODULE_RING)
        self.assertEqual((result["loops"], result["pairs"]), ([], []))
        self.assertEqual(result["mod_loops"], [["p", "q", "r"]])
        self.assertEqual(status, 1)

    def test_layered_crate_passes(self):
        result, status = run(LAYERED)
        self.assertEqual((result["loops"], result["mod_loops"], result["pairs"]), ([], [], []))
        self.assertEqual(status, 0)
        graph = result["graph"]
        # The edges are seen (so the pass is not for want of edges).
        self.assertIn("src/rules/rule.rs", graph["src/rules/mod.rs"])
        self.assertIn("src/rules/rule.rs", graph["src/rules/table.rs"])
        self.assertIn("src/rules/table.rs", graph["src/analysis/run.rs"])
        self.assertIn("src/rules/mod.rs", graph["src/analysis/run.rs"])
        self.assertIn("src/analysis/run.rs", graph["src/cli/mod.rs"])
        self.assertIn("src/cli/args.rs", graph["src/cli/mod.rs"])
        self.assertIn("src/cli/mod.rs", graph["src/main.rs"])
        self.assertEqual(graph["src/rules/rule.rs"], set())
        self.assertEqual(result["modgraph"]["rules"], set())

    def test_known_findings_pass_and_only_they(self):
        listed = "# still to remove\nfiles src/a/mod.rs src/a/child.rs\n"
        self.assertEqual(run(PARENT_CHILD_LOOP, listed)[1], 0)
        # a loop not listed fails
        self.assertEqual(run(PARENT_CHILD_LOOP, "")[1], 1)
        # a listed loop that no longer occurs fails: the list only shrinks
        self.assertEqual(run(LAYERED, listed)[1], 1)
        self.assertEqual(run(TWO_WAY_PAIR, "pair y x\nmodules x y\n")[1], 0)
        self.assertEqual(run(TWO_WAY_PAIR, "pair x z\nmodules x y\n")[1], 1)
        self.assertEqual(run(MODULE_RING, "modules r q p\n")[1], 0)


if __name__ == "__main__":
    unittest.main()
