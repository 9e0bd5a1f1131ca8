//! Loop subdivision of a closed triangle OBJ with the library functions
//! (`mesh::loop_subdivision`), for the comparison scripts
//! `benches/cgal/compare_loop.sh` and `benches/opensubdiv/compare_loop.sh`
//! (until `subdiv-lab subdivide --scheme loop` exists).
//!
//! ```text
//! cargo run --release --example loop_subdivide -- IN.obj LEVELS [OUT.obj] [--limit] [--timing]
//! ```
//!
//! Writes the refined mesh (with `--limit`: the refined mesh with every vertex
//! moved to its limit position) to `OUT.obj`; with `--timing` prints
//! `refinement: L levels, F faces, V vertices, T s` to standard error, `T`
//! the wall time of the refinement alone (not reading, limit or writing).
//! Refuses (exit 2) a request whose work estimate exceeds the limits the
//! `subdivide` command applies without `--force`.

use anyhow::{anyhow, bail, Context, Result};
use std::io::Write;
use subdiv_lab::budget::{format_bytes, format_seconds, MEMORY_LIMIT_BYTES, TIME_LIMIT_SECONDS};
use subdiv_lab::mesh::loop_subdivision::{half_edges_after, limit_mesh, refine};
use subdiv_lab::mesh::obj;

fn run() -> Result<()> {
    let mut positional = Vec::new();
    let (mut limit, mut timing) = (false, false);
    for a in std::env::args().skip(1) {
        match a.as_str() {
            "--limit" => limit = true,
            "--timing" => timing = true,
            _ => positional.push(a),
        }
    }
    let (input, levels, output) = match positional.as_slice() {
        [i, l] => (i, l, None),
        [i, l, o] => (i, l, Some(o)),
        _ => bail!("usage: loop_subdivide IN.obj LEVELS [OUT.obj] [--limit] [--timing]"),
    };
    let levels: usize = levels
        .parse()
        .map_err(|_| anyhow!("LEVELS: {levels:?} is not a non-negative integer"))?;
    let text = std::fs::read_to_string(input).with_context(|| format!("cannot read {input}"))?;
    let (mut mesh, _) = obj::parse_obj(&text).with_context(|| input.clone())?;
    let e = subdiv_lab::budget::subdivide(half_edges_after(&mesh, levels));
    if !e.within_limits(TIME_LIMIT_SECONDS, MEMORY_LIMIT_BYTES) {
        bail!(
            "{levels} levels need about {} and {} for {}, above the limits",
            format_bytes(e.bytes),
            format_seconds(e.seconds),
            e.what
        );
    }
    let t = std::time::Instant::now();
    for _ in 0..levels {
        mesh = refine(&mesh)?;
    }
    let secs = t.elapsed().as_secs_f64();
    if timing {
        eprintln!(
            "refinement: {levels} levels, {} faces, {} vertices, {secs:.6} s",
            mesh.face_count(),
            mesh.vertex_count()
        );
    }
    if let Some(path) = output {
        let out = if limit { limit_mesh(&mesh)? } else { mesh };
        let mut w = std::io::BufWriter::new(
            std::fs::File::create(path).with_context(|| format!("cannot create {path}"))?,
        );
        obj::write_obj(&out, &mut w)?;
        w.flush()?;
    }
    Ok(())
}

fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e:#}");
        std::process::exit(2);
    }
}
