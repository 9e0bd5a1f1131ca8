//! The automatic layout check of the report figures: every figure
//! kind of the registry is rendered (the default report plus small samples
//! of the kinds it does not use) and its SVG is checked for
//!
//! * **overlapping text**: every `<text>` gets a box estimated from its font
//!   size, its string length (per-character widths of DejaVu Sans, below), its
//!   anchor, baseline shift and rotation; no two boxes may overlap by more
//!   than [`OVERLAP_SLACK`] of the smaller font size (none);
//! * **text and legends inside the canvas**: every text box lies inside the
//!   SVG's `width` x `height` (up to [`CANVAS_SLACK`] pixels);
//! * **no negative zero** in any text (`-0`, `-0.0`, ...);
//! * **equal aspect** where the kind promises it (the complex plane of
//!   `spectrum`, the unit square of `knot-map`): on every panel, the pixels
//!   per unit of the x-axis tick labels and of the y-axis tick labels agree
//!   within [`ASPECT_TOL`].
//!
//! The checks read only the SVG text, so they cover every kind the same way;
//! a new kind needs one sample spec in [`samples`] (the test fails naming a
//! kind without one). The `planted_*` tests show that each check can fail.

use std::collections::BTreeMap;
use subdiv_lab::report::figures::{NoProgress, REGISTRY};
use subdiv_lab::report::{generate_with, Inputs, Options, ReportSpec, RunInfo};

/// Boxes may overlap by this fraction of the smaller font size (in both
/// directions) before it counts: none. The boxes are em boxes (they include
/// the space above the digits and below the baseline), so two boxes that
/// touch still leave a visible gap between the glyphs, while any overlap is
/// the kind a reader sees: corner ticks "0.0" of two axes that overlap by
/// 12 x 3 px are caught with this value, but not with a slack of 0.15 em.
const OVERLAP_SLACK: f64 = 0.0;
/// Pixels a text box may reach beyond the canvas edge (antialiasing; the
/// estimate is not exact to the pixel).
const CANVAS_SLACK: f64 = 2.0;
/// Relative difference allowed between the x and y scales of an
/// equal-aspect panel: tick labels sit at whole pixels, so with tick spans
/// of 150 px or more the rounding error is below 1.5%.
const ASPECT_TOL: f64 = 0.02;

/// Kinds whose plots promise an equal aspect ratio.
const EQUAL_ASPECT: &[&str] = &["spectrum", "knot-map"];

/// Advance width of a character of DejaVu Sans, in em (rounded up by class).
fn char_width(c: char) -> f64 {
    match c {
        ' ' => 0.32,
        'i' | 'l' | 'j' | '.' | ',' | ':' | ';' | '!' | '\'' | '|' => 0.3,
        'f' | 't' | 'r' | 'I' | '(' | ')' | '[' | ']' | '1' | '-' => 0.42,
        'm' | 'w' | 'M' | 'W' | '@' => 0.95,
        'A'..='Z' => 0.72,
        _ => 0.62,
    }
}

#[derive(Clone, Debug)]
struct TextBox {
    text: String,
    size: f64,
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
    /// Attributes for tick detection.
    anchor: String,
    dy: String,
    rotated: bool,
    x: f64,
    y: f64,
}

/// The text boxes of an SVG and its canvas size.
fn text_boxes(svg: &str) -> (Vec<TextBox>, (f64, f64)) {
    let doc = roxmltree::Document::parse(svg).expect("SVG parses");
    let root = doc.root_element();
    let num = |n: &roxmltree::Node, a: &str| -> f64 {
        n.attribute(a)
            .and_then(|v| v.trim_end_matches("px").parse().ok())
            .unwrap_or(0.0)
    };
    let canvas = (num(&root, "width"), num(&root, "height"));
    let mut out = Vec::new();
    for n in root.descendants().filter(|n| n.has_tag_name("text")) {
        let text: String = n
            .children()
            .filter_map(|d| d.text())
            .collect::<String>()
            .trim()
            .to_owned();
        if text.is_empty() {
            continue;
        }
        let (x, y, size) = (num(&n, "x"), num(&n, "y"), num(&n, "font-size"));
        let w: f64 = text.chars().map(char_width).sum::<f64>() * size;
        let h = size;
        let anchor = n.attribute("text-anchor").unwrap_or("start").to_owned();
        let dy = n.attribute("dy").unwrap_or("").to_owned();
        // Along the text direction: [a0, a1] relative to the anchor point.
        let (a0, a1) = match anchor.as_str() {
            "middle" => (-w / 2.0, w / 2.0),
            "end" => (-w, 0.0),
            _ => (0.0, w),
        };
        // Across it ("down" in the text's frame): [b0, b1].
        let (b0, b1) = match dy.as_str() {
            "0.76em" => (0.0, h),
            "0.5ex" => (-h / 2.0, h / 2.0),
            "-0.5ex" => (-h, 0.0),
            _ => (-0.76 * h, 0.24 * h),
        };
        let transform = n.attribute("transform").unwrap_or("");
        let rotated = transform.starts_with("rotate(270") || transform.starts_with("rotate(-90");
        let (x0, y0, x1, y1) = if rotated {
            // rotate(270): the text direction is up (-y), "down" is +x.
            (x + b0, y - a1, x + b1, y - a0)
        } else if transform.starts_with("rotate(90") {
            (x - b1, y + a0, x - b0, y + a1)
        } else {
            (x + a0, y + b0, x + a1, y + b1)
        };
        out.push(TextBox {
            text,
            size,
            x0,
            y0,
            x1,
            y1,
            anchor,
            dy,
            rotated,
            x,
            y,
        });
    }
    (out, canvas)
}

/// Problems of an SVG (empty: passes). `equal_aspect`: check the tick scales.
fn layout_problems(name: &str, svg: &str, equal_aspect: bool) -> Vec<String> {
    let (boxes, (w, h)) = text_boxes(svg);
    let mut problems = Vec::new();
    for (i, a) in boxes.iter().enumerate() {
        for b in &boxes[..i] {
            let s = OVERLAP_SLACK * a.size.min(b.size);
            let ox = a.x1.min(b.x1) - a.x0.max(b.x0);
            let oy = a.y1.min(b.y1) - a.y0.max(b.y0);
            if ox > s && oy > s {
                problems.push(format!(
                    "{name}: text {:?} at ({:.0}, {:.0}) overlaps {:?} at ({:.0}, {:.0}) by {ox:.0} x {oy:.0} px",
                    a.text, a.x, a.y, b.text, b.x, b.y
                ));
            }
        }
        if a.x0 < -CANVAS_SLACK
            || a.y0 < -CANVAS_SLACK
            || a.x1 > w + CANVAS_SLACK
            || a.y1 > h + CANVAS_SLACK
        {
            problems.push(format!(
                "{name}: text {:?} box ({:.0}, {:.0})-({:.0}, {:.0}) leaves the {w} x {h} canvas",
                a.text, a.x0, a.y0, a.x1, a.y1
            ));
        }
        let t = a.text.trim_start_matches(['-', '−']);
        if a.text.len() != t.len() && t.parse::<f64>() == Ok(0.0) {
            problems.push(format!("{name}: negative zero {:?}", a.text));
        }
    }
    if equal_aspect {
        problems.extend(aspect_problems(name, &boxes));
    }
    problems
}

/// A run of tick labels of one axis of one panel: (pixel, value) pairs.
type Ticks = Vec<(f64, f64)>;

/// Splits tick labels sharing one pixel coordinate into panels: within a
/// panel the values run monotonically (increasing with `pixel` on x axes,
/// decreasing on y axes); a reversal starts the next panel.
fn split_panels(mut t: Ticks, increasing: bool) -> Vec<Ticks> {
    t.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out: Vec<Ticks> = Vec::new();
    for p in t {
        match out.last_mut() {
            Some(cur) if (p.1 > cur.last().unwrap().1) == increasing => cur.push(p),
            _ => out.push(vec![p]),
        }
    }
    out.retain(|g| g.len() >= 2);
    out
}

/// Pixels per unit of a run of ticks (from its first and last label).
fn scale(t: &Ticks) -> f64 {
    let (a, b) = (t[0], t[t.len() - 1]);
    ((b.0 - a.0) / (b.1 - a.1)).abs()
}

fn aspect_problems(name: &str, boxes: &[TextBox]) -> Vec<String> {
    let value = |b: &TextBox| b.text.parse::<f64>().ok();
    let mut xs: BTreeMap<i64, Ticks> = BTreeMap::new();
    let mut ys: BTreeMap<i64, Ticks> = BTreeMap::new();
    for b in boxes.iter().filter(|b| !b.rotated) {
        let Some(v) = value(b) else { continue };
        if b.anchor == "middle" && b.dy == "0.76em" {
            xs.entry(b.y.round() as i64).or_default().push((b.x, v));
        } else if b.anchor == "end" && b.dy == "0.5ex" {
            ys.entry(b.x.round() as i64).or_default().push((b.y, v));
        }
    }
    // x runs: (axis y, first pixel x, scale); y runs: (axis x, last pixel y, scale).
    let xr: Vec<(f64, f64, f64)> = xs
        .into_iter()
        .flat_map(|(y, t)| {
            split_panels(t, true)
                .into_iter()
                .map(move |g| (y as f64, g[0].0, scale(&g)))
        })
        .collect();
    let yr: Vec<(f64, f64, f64)> = ys
        .into_iter()
        .flat_map(|(x, t)| {
            split_panels(t, false)
                .into_iter()
                .map(move |g| (x as f64, g[g.len() - 1].0, scale(&g)))
        })
        .collect();
    let mut problems = Vec::new();
    let mut panels = 0;
    for &(ax, bottom, sy) in &yr {
        // The x axis of the same panel: to the right of the y labels and
        // below them, the nearest such.
        let best = xr
            .iter()
            .filter(|(y, x, _)| *x >= ax - 1.0 && *y >= bottom - 1.0)
            .min_by(|a, b| {
                let d = |r: &(f64, f64, f64)| (r.1 - ax) + (r.0 - bottom);
                d(a).total_cmp(&d(b))
            });
        // Vertical labels without an x axis below them (a colour bar) are
        // not a panel.
        let Some(&(_, _, sx)) = best else { continue };
        panels += 1;
        if ((sx - sy) / sy).abs() > ASPECT_TOL {
            problems.push(format!(
                "{name}: panel with y labels at x = {ax}: {sx:.2} px per unit across, {sy:.2} up (equal aspect promised)"
            ));
        }
    }
    if panels == 0 {
        problems.push(format!(
            "{name}: promises an equal aspect but has no panel with tick labels on both axes"
        ));
    }
    problems
}

/// A small sweep CSV: valences 3 and 4 over a 2-D ratio grid, with one
/// cell of a long class name.
fn sweep_csv() -> String {
    let mut s =
        String::from("# subdiv-lab sweep: test data\nid,valence,r0,r1,r2,class,contraction_rate\n");
    let mut id = 0;
    for n in [3, 4] {
        for i in 0..9 {
            for j in 0..9 {
                let (r0, r1) = (0.05 + 0.1 * i as f64, 0.05 + 0.1 * j as f64);
                // One cell of the long class name the classifier writes
                // (its legend entry must wrap inside the canvas).
                let class = if i == 8 && j == 8 {
                    "indeterminate:standard/defective"
                } else if (r0 - 0.45f64).abs() < 1e-9 {
                    "defective"
                } else if (r0 < 0.5) == (r1 < 0.5) {
                    "complex_pair"
                } else {
                    "real_distinct"
                };
                s.push_str(&format!(
                    "{id},{n},{r0},{r1},0.5,{class},{}\n",
                    0.3 + 0.05 * (r0 + r1)
                ));
                id += 1;
            }
        }
    }
    s
}

/// Small specs for kinds the default report does not use, and for layouts
/// it does not reach (a single-panel spectrum, every sweep plot kind).
fn samples() -> &'static str {
    r#"
name = "layout-samples"
seed = 3

[[figure]]
kind = "spectrum"
id = "spectrum-single"
width = 900
height = 700
configs = [{ scheme = "nurds", ratios = [0.3, 0.6, 0.5] }]

[[figure]]
kind = "knot-map"
id = "knot-map-small"
width = 1000
height = 450
slices = [[0.5]]
grid = 15
color_by = "angle"

[[figure]]
kind = "certified-map"
id = "certified-map-small"
slices = [0.3, 0.7]
min_width = 0.0625
grid = 12

[[figure]]
kind = "sweep"
id = "sweep-default"
path = "sweep.csv"

[[figure]]
kind = "sweep"
id = "sweep-map"
path = "sweep.csv"
plot = "map"

[[figure]]
kind = "sweep"
id = "sweep-histogram"
path = "sweep.csv"
plot = "histogram"
color = "class"

[[figure]]
kind = "sweep"
id = "sweep-scatter"
path = "sweep.csv"
plot = "scatter"
x = "r0"
y = "contraction_rate"
color = "r1"
"#
}

fn render(spec_text: &str) -> Vec<(String, &'static str, String)> {
    let spec = ReportSpec::parse(spec_text).expect("spec parses");
    let mut inputs = Inputs::default();
    inputs.insert("sweep.csv", sweep_csv().into_bytes());
    let options = Options {
        formats: "svg".parse().unwrap(),
        inputs,
    };
    let report = generate_with(&spec, &RunInfo::default(), &NoProgress, &options).expect("renders");
    let files: BTreeMap<&str, &[u8]> = report
        .files
        .iter()
        .map(|f| (f.path.as_str(), f.bytes.as_slice()))
        .collect();
    report
        .manifest
        .figures
        .iter()
        .filter_map(|f| {
            let svg = f.svg.as_ref()?;
            Some((
                svg.clone(),
                f.kind,
                String::from_utf8(files[svg.as_str()].to_vec()).unwrap(),
            ))
        })
        .collect()
}

#[test]
fn every_figure_kind_passes_the_layout_check() {
    let mut rendered = render(include_str!("../../analysis/default.toml"));
    rendered.extend(render(samples()));
    let spec_kinds: Vec<&str> = ReportSpec::parse(include_str!("../../analysis/default.toml"))
        .unwrap()
        .figures
        .iter()
        .chain(ReportSpec::parse(samples()).unwrap().figures.iter())
        .map(|f| f.common.kind)
        .collect();
    for k in REGISTRY {
        assert!(
            spec_kinds.contains(&k.name),
            "figure kind {:?} has no sample in the layout test: add one to samples()",
            k.name
        );
    }
    let mut problems = Vec::new();
    for (name, kind, svg) in &rendered {
        problems.extend(layout_problems(name, svg, EQUAL_ASPECT.contains(kind)));
    }
    assert!(
        problems.is_empty(),
        "{} layout problems:\n{}",
        problems.len(),
        problems.join("\n")
    );
}

/// The default report's spectra with one SVG edit applied.
fn spectra_svg() -> String {
    let spec = include_str!("../../analysis/default.toml");
    let one = &spec[..spec
        .find("[[figure]]\nkind = \"subdominant-vs-valence\"")
        .unwrap()];
    let r = render(one);
    assert_eq!(r.len(), 1);
    let svg = r[0].2.clone();
    assert!(layout_problems("spectra", &svg, true).is_empty());
    svg
}

#[test]
fn planted_overlap_is_caught() {
    let svg = spectra_svg();
    // Copy the first text element 4 px to the right of itself.
    let start = svg.find("<text ").unwrap();
    let end = start + svg[start..].find("</text>").unwrap() + "</text>".len();
    let el = &svg[start..end];
    let xs = el.find(" x=\"").unwrap() + 4;
    let xe = xs + el[xs..].find('"').unwrap();
    let x: i64 = el[xs..xe].parse().unwrap();
    let moved = format!("{}{}{}", &el[..xs], x + 4, &el[xe..]);
    let planted = format!("{}{moved}\n{}", &svg[..end + 1], &svg[end + 1..]);
    let p = layout_problems("planted", &planted, false);
    assert!(p.iter().any(|m| m.contains("overlaps")), "{p:?}");
}

#[test]
fn planted_text_outside_the_canvas_is_caught() {
    let svg = spectra_svg();
    let planted = svg.replace(
        "</svg>",
        "<text x=\"1790\" y=\"600\" font-size=\"30\">|z| = 3/4</text>\n</svg>",
    );
    let p = layout_problems("planted", &planted, false);
    assert!(p.iter().any(|m| m.contains("leaves the")), "{p:?}");
}

#[test]
fn planted_negative_zero_and_unequal_aspect_are_caught() {
    let svg = spectra_svg();
    let planted = svg.replace(
        "</svg>",
        "<text x=\"900\" y=\"600\" font-size=\"20\">-0.0</text>\n</svg>",
    );
    let p = layout_problems("planted", &planted, false);
    assert!(p.iter().any(|m| m.contains("negative zero")), "{p:?}");
    // Stretch the y tick labels of the top row of panels by 10% about a
    // line below them (y = 560 px): the panels' scales now differ.
    let doc_boxes = text_boxes(&svg).0;
    let mut stretched = svg.clone();
    for b in doc_boxes
        .iter()
        .filter(|b| b.anchor == "end" && b.dy == "0.5ex" && b.y < 560.0)
    {
        let old = format!("x=\"{}\" y=\"{}\"", b.x, b.y);
        let new = format!(
            "x=\"{}\" y=\"{}\"",
            b.x,
            (560.0 - (560.0 - b.y) * 1.1).round()
        );
        stretched = stretched.replacen(&old, &new, 1);
    }
    let p = layout_problems("planted", &stretched, true);
    assert!(
        p.iter().any(|m| m.contains("equal aspect promised")),
        "{p:?}"
    );
}
