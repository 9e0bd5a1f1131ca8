//! The sweep's output paths against each other: the typed Parquet path
//! against the CSV text fed to the Parquet writer, and the shard merge of
//! CSV lines.

use std::sync::{Arc, Mutex};
use subdiv_lab::sweep::eval::{Cell, Evaluate, SpectralEvaluator};
use subdiv_lab::sweep::output::merge;
use subdiv_lab::sweep::output::parquet::{
    csv_lines, read_table, run_parquet, ParquetRows, PART_ROWS,
};
use subdiv_lab::sweep::output::parquet::{parse_part_name, part_name};
use subdiv_lab::sweep::output::{format_number, output_shape, read_output};
use subdiv_lab::sweep::output::{run, MergeSource};
use subdiv_lab::sweep::{Configuration, Layout, Plan, Shard, Summary, SweepError};
use subdiv_lab::table::{Column, Table};

/// An evaluator that returns the wrong number of cells for odd ids and fails
/// for ids divisible by 5, to exercise the error rows of the fast path.
struct Faulty(SpectralEvaluator);

impl Evaluate for Faulty {
    fn evaluate(
        &self,
        plan: &Plan,
        c: &Configuration,
        scheme: &dyn subdiv_lab::Scheme,
    ) -> subdiv_lab::spectral::Result<Vec<Cell>> {
        let mut v = self.0.evaluate(plan, c, scheme)?;
        if c.id % 5 == 0 {
            return Err(subdiv_lab::Error::InvalidParameter {
                name: "test",
                value: format!("id {}", c.id),
                reason: "a failure with a comma, and \"quotes\"",
            }
            .into());
        }
        if c.id % 2 == 1 {
            v.push(Cell::Text("extra".into()));
        }
        Ok(v)
    }
}

/// Cells of every kind from the id alone (no eigenvalues: cheap enough
/// for several row groups): labels with commas, quotes, line breaks and
/// empty text, NaN (with a payload), -0, infinities, booleans; the class
/// is one of a few values.
struct Synthetic;

impl Evaluate for Synthetic {
    fn evaluate(
        &self,
        _plan: &Plan,
        c: &Configuration,
        _scheme: &dyn subdiv_lab::Scheme,
    ) -> subdiv_lab::spectral::Result<Vec<Cell>> {
        let id = c.id;
        if id % 997 == 13 {
            return Err(subdiv_lab::Error::InvalidParameter {
                name: "test",
                value: format!("id {id}"),
                reason: "a failure with a comma, \"quotes\"\nand a line break",
            }
            .into());
        }
        let class = [
            "standard",
            "real_distinct",
            "complex_pair",
            "a,b",
            "q\"uote",
            "x\ny",
            "",
        ];
        let num = |k: u64| match (id + k) % 11 {
            0 => Cell::Empty,
            1 => Cell::Num(f64::from_bits(0x7ff8_0000_0000_0abc)),
            2 => Cell::Num(-0.0),
            3 => Cell::Num(f64::INFINITY),
            4 => Cell::Num(f64::NEG_INFINITY),
            5 => Cell::Num(1e-300 * (id as f64)),
            _ => Cell::Num((id as f64 + k as f64).sqrt() / 7.0),
        };
        let mut v = vec![Cell::Text(class[(id % 7) as usize].to_owned())];
        v.extend((0..10).map(num));
        v.push(Cell::Text(
            ["undecided", "standard"][(id % 2) as usize].to_owned(),
        ));
        v.push(match id % 3 {
            0 => Cell::Text("true".into()),
            1 => Cell::Text("false".into()),
            _ => Cell::Empty,
        });
        Ok(v)
    }
}

/// A Parquet file in memory, its row groups' rows, the summary.
type Written = (Vec<u8>, Vec<u64>, Summary);

/// A writer into a shared buffer (`ParquetRows::file` takes its writer).
#[derive(Clone, Default)]
struct Shared(Arc<Mutex<Vec<u8>>>);

impl std::io::Write for Shared {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0
            .lock()
            .map_err(|_| std::io::Error::other("poisoned"))?
            .extend_from_slice(buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

impl Shared {
    fn bytes(&self) -> Vec<u8> {
        self.0.lock().unwrap().clone()
    }
}

/// The rows of one file of row groups written into a [`Shared`] buffer.
fn file_rows(layout: &Layout, fp: &str) -> (ParquetRows, Shared) {
    let buf = Shared::default();
    (
        ParquetRows::file(layout, fp, Box::new(buf.clone())).unwrap(),
        buf,
    )
}

/// Rows of each row group of a file (from its footer).
fn group_rows(bytes: &[u8]) -> Vec<u64> {
    use parquet::file::reader::FileReader;
    let r = parquet::file::reader::SerializedFileReader::new(bytes::Bytes::from(bytes.to_vec()))
        .unwrap();
    r.metadata()
        .row_groups()
        .iter()
        .map(|g| g.num_rows() as u64)
        .collect()
}

/// The Parquet file of `run_parquet` (the typed path) and of `run`'s CSV
/// lines fed to `ParquetRows` as text (the path merge uses), with their
/// summaries and commits.
fn both_paths<E: Evaluate>(
    plan: &Plan,
    layout: &Layout,
    eval: &E,
    ids: &[u64],
    threads: usize,
) -> (Written, Written) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let file = |typed: bool| {
        let mut summary = Summary::new(plan, layout, Shard::ALL, None);
        let fp = subdiv_lab::sweep::output::fingerprint_line(plan, Shard::ALL);
        let (mut rows, buf) = file_rows(layout, &fp);
        pool.install(|| {
            if typed {
                run_parquet(
                    plan,
                    layout,
                    eval,
                    ids.iter().copied(),
                    &mut rows,
                    &mut summary,
                    &mut |_| {},
                    &std::sync::atomic::AtomicU64::new(0),
                )
            } else {
                run(
                    plan,
                    layout,
                    eval,
                    ids.iter().copied(),
                    &mut rows,
                    &mut summary,
                    &mut |_| {},
                )
            }
        })
        .unwrap();
        rows.finish().unwrap();
        let bytes = buf.bytes();
        let groups = group_rows(&bytes);
        (bytes, groups, summary)
    };
    (file(true), file(false))
}

/// The typed path writes the bytes the CSV-text path writes (values,
/// nulls, labels, booleans, errors, row groups and footers), with the
/// same summary, for any thread count; across several row groups.
#[test]
fn typed_parquet_path_equals_the_csv_text_path() {
    let spec = "scheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.01, 0.99]\n[sampler]\nkind = \"halton\"\ncount = 140000\n[columns]\nexact_certificate = true\n";
    let plan = Plan::new(subdiv_lab::sweep::SweepSpec::from_toml(spec).unwrap());
    let layout = Layout::new(&plan);
    // Rows of a resumed run start mid-sweep; an out-of-range id is an error row.
    let ids: Vec<u64> = (5..plan.total()).chain([plan.total() + 3]).collect();
    for threads in [1, 3] {
        let (typed, text) = both_paths(&plan, &layout, &Synthetic, &ids, threads);
        assert_eq!(typed.1, text.1, "row groups");
        assert_eq!(typed.1.len(), 3);
        assert_eq!(typed.1[0], PART_ROWS as u64);
        assert!(typed.0 == text.0, "the two paths' bytes differ");
        assert_eq!(typed.2, text.2);
        let t = read_table(typed.0).unwrap();
        assert_eq!(t.len(), ids.len());
        // Line breaks are spaces in both forms; NaN reads back as NaN.
        assert!(csv_lines(&t, 0, 20).contains("x y"));
    }
    // The built-in evaluator, and error rows of a faulty one.
    let small = "scheme = \"nurds\"\nvalences = [3, 5]\n[space]\nkind = \"corner-intervals\"\ninterval_range = [0.001, 1000.0]\n[sampler]\nkind = \"random\"\ncount = 300\nseed = 5\n[columns]\neigenvalues = 4\nexact_certificate = true\n";
    let plan = Plan::new(subdiv_lab::sweep::SweepSpec::from_toml(small).unwrap());
    let layout = Layout::new(&plan);
    let ids: Vec<u64> = (0..plan.total()).collect();
    let eval = SpectralEvaluator::new(plan.spec().columns);
    let (typed, text) = both_paths(&plan, &layout, &eval, &ids, 2);
    assert!(typed.0 == text.0);
    assert_eq!(typed.2, text.2);
    let (typed, text) = both_paths(&plan, &layout, &Faulty(eval), &ids, 2);
    assert!(typed.0 == text.0);
    assert_eq!(typed.2, text.2);
}

/// The driver recycles its row blocks from the third chunk on: over many
/// chunks, both paths write the bytes of the per-row CSV text
/// (`Layout::row` + `format_into`, no row blocks) fed to `ParquetRows`.
#[test]
fn recycled_row_blocks_write_the_rows_of_the_per_row_path() {
    use std::io::Write;
    let spec = "scheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.01, 0.99]\n[sampler]\nkind = \"halton\"\ncount = 18000\n[columns]\neigenvalues = 2\n";
    let plan = Plan::new(subdiv_lab::sweep::SweepSpec::from_toml(spec).unwrap());
    let layout = Layout::new(&plan);
    let eval = SpectralEvaluator::new(plan.spec().columns);
    let ids: Vec<u64> = (0..plan.total()).collect();
    assert!(ids.len() > 4 * subdiv_lab::sweep::output::CHUNK);
    let mut text = String::new();
    for &id in &ids {
        let r = layout.row(&plan, &eval, id);
        layout.format_into(&r, &mut text);
    }
    let fp = subdiv_lab::sweep::output::fingerprint_line(&plan, Shard::ALL);
    let (mut rows, buf) = file_rows(&layout, &fp);
    rows.write_all(text.as_bytes()).unwrap();
    rows.finish().unwrap();
    let want = buf.bytes();
    for threads in [1, 2] {
        let (typed, csv) = both_paths(&plan, &layout, &eval, &ids, threads);
        assert!(typed.0 == want, "typed path, {threads} threads");
        assert!(csv.0 == want, "CSV path, {threads} threads");
    }
}

/// A cell that does not fit its column is refused by both paths; the
/// typed path names the configuration, the column and the value.
#[test]
fn typed_parquet_path_refuses_a_cell_of_the_wrong_kind() {
    struct TextInFloat;
    impl Evaluate for TextInFloat {
        fn evaluate(
            &self,
            _plan: &Plan,
            c: &Configuration,
            _scheme: &dyn subdiv_lab::Scheme,
        ) -> subdiv_lab::spectral::Result<Vec<Cell>> {
            let mut v = vec![Cell::Text("standard".into())];
            v.extend((0..5).map(|_| Cell::Num(0.5)));
            v[2] = if c.id == 4 {
                Cell::Text("oops".into())
            } else {
                Cell::Text("0.25".into())
            };
            Ok(v)
        }
    }
    let spec = "scheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n[columns]\ngap = false\ncontraction = false\n";
    let plan = Plan::new(subdiv_lab::sweep::SweepSpec::from_toml(spec).unwrap());
    let layout = Layout::new(&plan);
    // Ids 0..4: a number as text in a float column reads as the number.
    let ids: Vec<u64> = (0..4).collect();
    let (typed, text) = both_paths(&plan, &layout, &TextInFloat, &ids, 1);
    assert!(typed.0 == text.0);
    let t = read_table(typed.0).unwrap();
    assert_eq!(
        t.column("lambda1_im"),
        Some(&Column::F64(vec![Some(0.25); 4]))
    );
    // Id 4: "oops" is not a number.
    let mut rows = file_rows(&layout, "fp").0;
    let mut summary = Summary::new(&plan, &layout, Shard::ALL, None);
    let e = run_parquet(
        &plan,
        &layout,
        &TextInFloat,
        0..8u64,
        &mut rows,
        &mut summary,
        &mut |_| {},
        &std::sync::atomic::AtomicU64::new(0),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("configuration 4") && e.contains("lambda1_im") && e.contains("\"oops\""),
        "{e}"
    );
    let mut out = file_rows(&layout, "fp").0;
    let mut summary = Summary::new(&plan, &layout, Shard::ALL, None);
    assert!(run(
        &plan,
        &layout,
        &TextInFloat,
        0..8u64,
        &mut out,
        &mut summary,
        &mut |_| {}
    )
    .is_err());
}

/// Synthetic cells with 41 distinct labels first seen in scrambled order
/// (beyond the dictionary's linear search), or, with `all_null`, every label
/// and boolean cell empty (columns without a single value).
struct ManyLabels {
    all_null: bool,
}

impl Evaluate for ManyLabels {
    fn evaluate(
        &self,
        plan: &Plan,
        c: &Configuration,
        scheme: &dyn subdiv_lab::Scheme,
    ) -> subdiv_lab::spectral::Result<Vec<Cell>> {
        let mut v = Synthetic.evaluate(plan, c, scheme)?;
        if self.all_null {
            for cell in &mut v {
                if matches!(cell, Cell::Text(_)) {
                    *cell = Cell::Empty;
                }
            }
        } else if c.id % 5 != 0 {
            v[0] = Cell::Text(format!("label-{}", (c.id * 7919) % 41));
        }
        Ok(v)
    }
}

/// The typed path's file for `count` Halton points read back (through the
/// arrow-rs reader, not our encoder), and the CSV text of the same rows;
/// asserts that the file reads back as exactly those CSV lines.
fn reads_back_as_csv(eval: &ManyLabels, count: u64) -> (Table, String) {
    let spec = format!("scheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.01, 0.99]\n[sampler]\nkind = \"halton\"\ncount = {count}\n[columns]\nexact_certificate = true\n");
    let plan = Plan::new(subdiv_lab::sweep::SweepSpec::from_toml(&spec).unwrap());
    let layout = Layout::new(&plan);
    let ids: Vec<u64> = (0..plan.total()).collect();
    let (typed, _) = both_paths(&plan, &layout, eval, &ids, 2);
    let mut csv: Vec<u8> = Vec::new();
    let mut summary = Summary::new(&plan, &layout, Shard::ALL, None);
    run(
        &plan,
        &layout,
        eval,
        ids.iter().copied(),
        &mut csv,
        &mut summary,
        &mut |_| {},
    )
    .unwrap();
    let t = read_table(typed.0).unwrap();
    let csv = String::from_utf8(csv).unwrap();
    let back = csv_lines(&t, 0, t.len());
    assert_eq!(back.lines().count(), csv.lines().count());
    for (k, (a, b)) in back.lines().zip(csv.lines()).enumerate() {
        assert_eq!(a, b, "row {k}");
    }
    (t, csv)
}

/// The file reads back as exactly the CSV lines of the same rows: over two
/// row groups, with more distinct labels than the dictionary's linear search
/// holds, nulls in every optional column, booleans of both values and nulls
/// (their bit packing), and error rows.
#[test]
fn parquet_reads_back_as_the_csv_lines() {
    let (t, csv) = reads_back_as_csv(&ManyLabels { all_null: false }, 70_000);
    assert_eq!(t.len(), 70_000);
    // Every kind of cell occurs.
    assert!(matches!(t.column("exact_agrees"), Some(Column::Bool(v))
        if v.contains(&Some(true)) && v.contains(&Some(false)) && v.contains(&None)));
    assert!(csv.contains("label-40") && csv.contains(",,"));
}

/// Label and boolean columns without a single value (an empty dictionary,
/// no boolean bits) read back as nulls.
#[test]
fn parquet_columns_of_nulls_read_back() {
    let (t, _) = reads_back_as_csv(&ManyLabels { all_null: true }, 300);
    assert!(matches!(t.column("class"), Some(Column::Str(v)) if v.iter().all(Option::is_none)));
    assert!(
        matches!(t.column("exact_agrees"), Some(Column::Bool(v)) if v.iter().all(Option::is_none))
    );
}

const EIGHT: &str = "scheme = \"nurds\"\nvalences = [3]\n[space]\nkind = \"ratios\"\nratio_range = [0.2, 0.8]\n[sampler]\nkind = \"grid\"\npoints_per_axis = 2\n";

type Lines = std::vec::IntoIter<Result<String, SweepError>>;

fn src(name: &str, shard: Shard, lines: &[&str]) -> MergeSource<Lines> {
    MergeSource {
        name: name.into(),
        shard,
        lines: lines
            .iter()
            .map(|l| Ok(l.to_string()))
            .collect::<Vec<_>>()
            .into_iter(),
    }
}

#[test]
fn merge_checks_ids_and_rows() {
    let plan = Plan::new(subdiv_lab::sweep::SweepSpec::from_toml(EIGHT).unwrap());
    let layout = Layout::new(&plan);
    let eval = SpectralEvaluator::new(plan.spec().columns);
    let mut all = Vec::new();
    run(
        &plan,
        &layout,
        &eval,
        0..8,
        &mut all,
        &mut Summary::new(&plan, &layout, Shard::ALL, None),
        &mut |_| {},
    )
    .unwrap();
    let all = String::from_utf8(all).unwrap();
    let l: Vec<&str> = all.lines().collect();
    let s0: Shard = "0/2".parse().unwrap();
    let s1: Shard = "1/2".parse().unwrap();
    let evens = [l[0], l[2], l[4], l[6]];
    let odds = [l[1], l[3], l[5], l[7]];
    let mut out = Vec::new();
    let parts = merge(
        &plan,
        &layout,
        &eval,
        vec![src("a", s0, &evens), src("b", s1, &odds)],
        &mut out,
        1,
    )
    .unwrap();
    assert_eq!(String::from_utf8(out).unwrap(), all);
    assert_eq!(parts.iter().map(|p| p.rows).collect::<Vec<_>>(), vec![4, 4]);
    let go = |srcs: Vec<MergeSource<Lines>>| {
        merge(&plan, &layout, &eval, srcs, &mut Vec::new(), 1)
            .unwrap_err()
            .to_string()
    };
    let e = go(vec![src("a", s0, &evens), src("b", s1, &odds[..3])]);
    assert!(e.contains("configuration id 7 is missing"), "{e}");
    let e = go(vec![
        src("a", s0, &evens),
        src("b", s1, &odds),
        src("c", s0, &evens[..1]),
    ]);
    assert!(e.contains("configuration id 0 appears twice"), "{e}");
    let e = go(vec![src("a", s0, &[l[0], l[1]])]);
    assert!(
        e.contains("a: line 3: configuration id 1 where 2 was expected"),
        "{e}"
    );
    // A bogus class, an edited number, an edited parameter.
    let bogus = l[2]
        .replacen(",standard,", ",bogus,", 1)
        .replacen(",real_distinct,", ",bogus,", 1)
        .replacen(",complex_pair,", ",bogus,", 1);
    assert_ne!(bogus, l[2]);
    let e = go(vec![
        src("a", s0, &[l[0], &bogus, l[4], l[6]]),
        src("b", s1, &odds),
    ]);
    assert!(e.contains("a: line 3: class = \"bogus\""), "{e}");
    let f: Vec<&str> = l[4].split(',').collect();
    let mut g = f.clone();
    let lam = format!("{}", f[6].parse::<f64>().unwrap() + 0.25);
    g[6] = &lam;
    let edited = g.join(",");
    let e = go(vec![
        src("a", s0, &[l[0], l[2], &edited, l[6]]),
        src("b", s1, &odds),
    ]);
    assert!(
        e.contains("a: line 4: configuration 4 differs from a fresh evaluation: lambda1_re"),
        "{e}"
    );
    let mut g = f.clone();
    g[2] = "0.5";
    let edited = g.join(",");
    let e = go(vec![
        src("a", s0, &[l[0], l[2], &edited, l[6]]),
        src("b", s1, &odds),
    ]);
    assert!(
        e.contains("configuration 4 has r0 = \"0.5\" where the spec gives"),
        "{e}"
    );
}

/// The CSV's numbers are Ryu's shortest round trip, byte for byte.
#[test]
fn numbers_are_written_as_ryu_writes_them() {
    // The CSV format is Ryu's shortest round trip; the digits come from
    // Zmij, so compare the two on random bit patterns, random values of
    // every magnitude and short decimals.
    let mut ryu_buf = ryu::Buffer::new();
    let mut check = |x: f64| {
        let s = format_number(x);
        let want = if x.is_finite() {
            ryu_buf.format_finite(x)
        } else {
            ""
        };
        if x.is_finite() {
            assert_eq!(s, want, "{x:e}");
        }
        assert_eq!(s.parse::<f64>().unwrap().to_bits(), x.to_bits(), "{s}");
    };
    for i in 0..200_000u64 {
        let h = subdiv_lab::rng::mix64(i);
        let bits = f64::from_bits(h);
        if !bits.is_nan() {
            check(bits);
        }
        let u = (h >> 11) as f64 / (1u64 << 53) as f64;
        let e = (subdiv_lab::rng::mix64(h) % 90) as i32 - 45;
        check(u * 10f64.powi(e));
        check(-u);
        check((h % 100_000) as f64 / 10f64.powi((h % 23) as i32));
    }
    for x in [
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.1,
        1e15,
        1e16,
        1e17,
        123_456_789_012_345_680.0,
        1e-5,
        1e-6,
        1e-7,
        f64::MIN_POSITIVE,
        5e-324,
        f64::MAX,
        f64::MIN,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ] {
        check(x);
    }
    assert_eq!(format_number(f64::NAN), "NaN");
    assert_eq!(format_number(f64::INFINITY), "inf");
    assert_eq!(format_number(1e16), "1e16");
    assert_eq!(format_number(1.0), "1.0");
}

/// Part names round-trip and nothing else parses as one.
#[test]
fn part_names_round_trip() {
    for (s, k) in [
        ("0/1", 0),
        ("0/1", 999_999),
        ("0/1", 1_234_567),
        ("3/7", 12),
    ] {
        let shard: Shard = s.parse().unwrap();
        assert_eq!(parse_part_name(&part_name(shard, k)), Some((shard, k)));
    }
    for bad in [
        "part-17.parquet",
        "part-0000017.parquet",
        "part-000017.parquet.tmp",
        "part-7-of-3-000001.parquet",
        "part-+1-of-3-000001.parquet",
        "part-1-of-03-000001.parquet",
        "part-1-of-3-+00001.parquet",
        "part-0-of-1-000001.parquet",
        "part- 1-of-3-000001.parquet",
        "part-1-of-3-000001.csv",
        "_summary.json",
    ] {
        assert_eq!(parse_part_name(bad), None, "{bad}");
    }
}

/// The shape is read without parsing: a bound of the rows (the lines)
/// and the header's fields; a Parquet file's from its footer.
#[test]
fn shape_bounds_rows_before_parsing() {
    let csv = b"# fingerprint\nid,valence,class\n0,3,a\n1,3,b\n";
    let (rows, cols) = output_shape("s.csv", csv).unwrap();
    assert_eq!(cols, 3);
    assert!(rows >= read_output("s.csv", csv).unwrap().len());
    assert!(output_shape("s.parquet", b"PAR1").is_err());
}
