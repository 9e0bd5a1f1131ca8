//! Mesh refinement throughput and peak memory.
//!
//! Input: the truncated icosahedron refined 4 times with the Catmull-Clark
//! variant (11,522 faces, 46,080 half-edges: hexagons, pentagons, valence-3
//! vertices). Each benchmark refines it 4 more times to 2,949,122 faces.
//!
//! * Throughput: divan's timing with `ItemsCount` = output faces, so the
//!   "items/s" column is output faces per second.
//! * Peak memory: before divan starts, each scheme is run once under a
//!   counting global allocator (`PeakAlloc` below wraps the system allocator
//!   and tracks live and peak heap bytes); the table printed first gives the
//!   peak heap above the baseline (input mesh already allocated) and bytes per
//!   output face. Whole-process peak RSS of the CLI is measured separately
//!   with `/usr/bin/time -v` by `benches/cgal/compare.sh`.
//!
//! Loop subdivision (`mesh::loop_subdivision`) has its own input,
//! a triangle mesh: the icosahedron refined 4 times with Loop (5,120
//! triangles), refined 4 more times to 1,310,720 triangles; same two
//! measurements. The comparison with CGAL and OpenSubdiv is
//! `benches/cgal/compare_loop.sh`.
//!
//! Run: `cargo bench --bench mesh`.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
use subdiv_lab::mesh::loop_subdivision as loop_mesh;
use subdiv_lab::mesh::refine::refine_levels;
use subdiv_lab::mesh::{generators, Mesh};
use subdiv_lab::schemes::SchemeKind;

struct PeakAlloc;
static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for PeakAlloc {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = LIVE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(now, Ordering::Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            if new_size >= layout.size() {
                let now = LIVE.fetch_add(new_size - layout.size(), Ordering::Relaxed)
                    + (new_size - layout.size());
                PEAK.fetch_max(now, Ordering::Relaxed);
            } else {
                LIVE.fetch_sub(layout.size() - new_size, Ordering::Relaxed);
            }
        }
        p
    }
}

#[global_allocator]
static GLOBAL: PeakAlloc = PeakAlloc;

const LEVELS: usize = 4;

fn input() -> Mesh {
    refine_levels(
        &generators::truncated_icosahedron(),
        SchemeKind::CcVariant,
        4,
    )
    .expect("input mesh")
}

fn input_with_knots() -> Mesh {
    let mut m = input();
    // deterministic non-uniform intervals in [0.25, 4]
    let k: Vec<f64> = (0..m.half_edge_count())
        .map(|h| 0.25 * 16f64.powf(((h as u64 * 2654435761) % 1000) as f64 / 999.0))
        .collect();
    m.set_knots(k).expect("valid knots");
    m
}

const SCHEMES: [SchemeKind; 3] = [
    SchemeKind::Nurds,
    SchemeKind::DooSabin,
    SchemeKind::CcVariant,
];

fn mesh_for(scheme: SchemeKind) -> Mesh {
    if scheme == SchemeKind::Nurds {
        input_with_knots()
    } else {
        input()
    }
}

fn memory_table() {
    println!("peak heap of refine_levels(input, scheme, {LEVELS}) (input: 11522 faces):");
    println!(
        "{:<11} {:>12} {:>10} {:>14} {:>16}",
        "scheme", "out faces", "time s", "peak heap MiB", "bytes/out face"
    );
    for scheme in SCHEMES {
        let m = mesh_for(scheme);
        let base = LIVE.load(Ordering::Relaxed);
        PEAK.store(base, Ordering::Relaxed);
        let t = std::time::Instant::now();
        let r = refine_levels(&m, scheme, LEVELS).expect("refine");
        let secs = t.elapsed().as_secs_f64();
        let peak = PEAK.load(Ordering::Relaxed) - base;
        println!(
            "{:<11} {:>12} {:>10.3} {:>14.1} {:>16.1}",
            scheme.name(),
            r.face_count(),
            secs,
            peak as f64 / (1 << 20) as f64,
            peak as f64 / r.face_count() as f64
        );
    }
    let m = loop_input();
    let base = LIVE.load(Ordering::Relaxed);
    PEAK.store(base, Ordering::Relaxed);
    let t = std::time::Instant::now();
    let r = loop_mesh::refine_levels(&m, LEVELS).expect("refine");
    let secs = t.elapsed().as_secs_f64();
    let peak = PEAK.load(Ordering::Relaxed) - base;
    println!(
        "{:<11} {:>12} {:>10.3} {:>14.1} {:>16.1}   (input: {} triangles)",
        "loop",
        r.face_count(),
        secs,
        peak as f64 / (1 << 20) as f64,
        peak as f64 / r.face_count() as f64,
        m.face_count()
    );
    println!();
}

/// The Loop input: the icosahedron refined 4 times with Loop (5,120 triangles).
fn loop_input() -> Mesh {
    loop_mesh::refine_levels(&generators::icosahedron(), 4).expect("loop input")
}

fn main() {
    memory_table();
    divan::main();
}

#[divan::bench(args = SCHEMES, sample_count = 5, sample_size = 1)]
fn refine_4_levels(bencher: divan::Bencher, scheme: SchemeKind) {
    let m = mesh_for(scheme);
    let out_faces = refine_levels(&m, scheme, LEVELS)
        .expect("refine")
        .face_count();
    bencher
        .counter(divan::counter::ItemsCount::new(out_faces))
        .bench(|| refine_levels(divan::black_box(&m), scheme, LEVELS).expect("refine"));
}

#[divan::bench(sample_count = 5, sample_size = 1)]
fn loop_refine_4_levels(bencher: divan::Bencher) {
    let m = loop_input();
    let out_faces = loop_mesh::refine_levels(&m, LEVELS)
        .expect("refine")
        .face_count();
    bencher
        .counter(divan::counter::ItemsCount::new(out_faces))
        .bench(|| loop_mesh::refine_levels(divan::black_box(&m), LEVELS).expect("refine"));
}
