//! The console sessions of the README and the guide (docs/guide/*.md) run against the binary built
//! from this tree, from the repository root, and their output is compared with
//! the text of the guide (`...` and `[..]` elide what varies, such as timings).
//! Commands that write files write them under `target/`, which the build
//! creates (the sessions name it so that a reader can run them as printed).
#[test]
fn guide_sessions() {
    std::fs::create_dir_all("target").expect("create target");
    trycmd::TestCases::new()
        .case("README.md")
        .case("docs/guide/*.md");
}
