//! The library's sweep-CSV verifier (`sweep::output::Verifier`, used by
//! `sweep --resume` and `sweep merge`), tested directly: the row
//! limit, the form rules of the result columns, the bottom-k recheck sample
//! and the summary it rebuilds. The CLI tests (`sweep_cli.rs`,
//! `hostile_inputs.rs`) exercise the same checks through the binary but edit
//! only `class` and `abs_lambda3`.

use subdiv_lab::rng::mix64;
use subdiv_lab::sweep::output::{self, format_number, LineFault, Verifier, RECHECK_SAMPLE};
use subdiv_lab::sweep::{Layout, Plan, Shard, SpectralEvaluator, Summary, SweepSpec};

/// A sweep's data lines (no header) and the summary
/// accumulated while writing them.
fn data_lines(plan: &Plan, layout: &Layout) -> (Vec<String>, Summary) {
    let eval = SpectralEvaluator::new(plan.spec().columns);
    let mut summary = Summary::new(plan, layout, Shard::ALL, None);
    let mut out = Vec::new();
    output::run(
        plan,
        layout,
        &eval,
        0..plan.total(),
        &mut out,
        &mut summary,
        &mut |_| {},
    )
    .unwrap();
    let text = String::from_utf8(out).unwrap();
    (text.lines().map(str::to_owned).collect(), summary)
}

/// Line number of data row `j` in a sweep CSV (the header first).
fn lineno(j: usize) -> u64 {
    j as u64 + 2
}

fn expected(j: u64) -> u64 {
    Shard::ALL.id(j)
}

fn block(lines: &[String]) -> Vec<u8> {
    lines
        .iter()
        .flat_map(|l| l.bytes().chain([b'\n']))
        .collect()
}

const SMALL: &str = r#"
scheme = "nurds"
valences = [3, 4]
[space]
kind = "ratios"
ratio_range = [0.05, 0.95]
[sampler]
kind = "random"
count = 6
seed = 3
[columns]
charmap = true
exact_certificate = true
"#;

/// Rows beyond the run's limit are refused at the first
/// such row, the limit counts the rows of earlier blocks, and a file of
/// exactly `max_rows` rows passes (an off-by-one in either direction fails).
#[test]
fn the_row_limit_is_exact_and_counts_earlier_blocks() {
    let plan = Plan::new(SweepSpec::from_toml(SMALL).unwrap());
    let layout = Layout::new(&plan);
    let (lines, _) = data_lines(&plan, &layout);
    let n = lines.len() as u64;
    assert_eq!(n, 12);
    let all = block(&lines);
    let mut v = Verifier::new(&plan, &layout, 1);
    assert_eq!(v.check_block(lineno(0), &all, Shard::ALL, n), Ok(n));
    assert_eq!(v.rows(), n);
    let mut v = Verifier::new(&plan, &layout, 1);
    assert_eq!(
        v.check_block(lineno(0), &all, Shard::ALL, n - 1),
        Err((lineno(lines.len() - 1), LineFault::TooManyRows))
    );
    // Two blocks: the second starts at row 5 of the file.
    let (a, b) = (block(&lines[..5]), block(&lines[5..]));
    for (limit, want) in [
        (n, Ok(n - 5)),
        (
            n - 1,
            Err((lineno(lines.len() - 1), LineFault::TooManyRows)),
        ),
    ] {
        let mut v = Verifier::new(&plan, &layout, 1);
        assert_eq!(v.check_block(lineno(0), &a, Shard::ALL, limit), Ok(5));
        assert_eq!(v.check_block(lineno(5), &b, Shard::ALL, limit), want);
    }
    // A limit inside the first block: refused at that row.
    let mut v = Verifier::new(&plan, &layout, 1);
    assert_eq!(
        v.check_block(lineno(0), &all, Shard::ALL, 4),
        Err((lineno(4), LineFault::TooManyRows))
    );
    // Rows out of order are a mismatch, not a limit.
    let mut swapped = lines.clone();
    swapped.swap(1, 2);
    let mut v = Verifier::new(&plan, &layout, 1);
    assert!(matches!(
        v.check_block(lineno(0), &block(&swapped), Shard::ALL, n),
        Err((l, LineFault::Mismatch(_))) if l == lineno(1)
    ));
}

/// Every text and ranged number column accepts exactly the values the sweep
/// writes (module documentation of `verify.rs`): checked by editing one cell
/// of a correct line at a time.
#[test]
fn result_cells_are_checked_against_their_column_rules() {
    let plan = Plan::new(SweepSpec::from_toml(SMALL).unwrap());
    let layout = Layout::new(&plan);
    let (lines, _) = data_lines(&plan, &layout);
    let names = layout.column_names();
    let column = |name: &str| {
        names
            .iter()
            .position(|n| n == name)
            .unwrap_or_else(|| panic!("no column {name} in {names:?}"))
    };
    let ruled = [
        "class",
        "charmap_verdict",
        "charmap_winding",
        "exact_class",
        "exact_agrees",
        "abs_lambda3",
        "contraction_rate",
    ];
    // a row without an error (empty last cell) and every ruled cell present
    let (j, line) = lines
        .iter()
        .enumerate()
        .find(|(_, l)| {
            let c: Vec<&str> = l.split(',').collect();
            !l.contains('"') && l.ends_with(',') && ruled.iter().all(|r| !c[column(r)].is_empty())
        })
        .expect("a complete row without an error");
    let cells: Vec<&str> = line.split(',').collect();
    assert_eq!(cells.len(), names.len(), "{names:?}");
    let verdict = |name: &str, value: &str| -> Result<u64, String> {
        let mut edited = cells.clone();
        edited[column(name)] = value;
        Verifier::new(&plan, &layout, 1).check(lineno(j), &edited.join(","), expected(j as u64))
    };
    assert_eq!(
        verdict("class", cells[column("class")]),
        Ok(expected(j as u64))
    );
    let classes = [
        "standard",
        "real_distinct",
        "complex_pair",
        "defective",
        "not_separated",
    ];
    let codes = [
        "c1",
        "tpc_real_distinct",
        "tpc_complex_pair",
        "tpc",
        "not_regular",
        "not_injective",
        "indeterminate",
        "no_charmap",
    ];
    let mut accepted: Vec<(&str, String)> = Vec::new();
    let mut refused: Vec<(&str, String)> = Vec::new();
    for c in classes {
        accepted.push(("class", c.into()));
        accepted.push(("exact_class", c.into()));
        accepted.push(("class", format!("indeterminate:{c}/standard")));
        accepted.push(("class", format!("indeterminate:defective/{c}")));
        refused.push(("charmap_verdict", c.into()));
        refused.push(("exact_class", format!("indeterminate:{c}/standard")));
    }
    for c in codes {
        accepted.push(("charmap_verdict", c.into()));
        if c != "indeterminate" {
            refused.push(("class", c.into()));
        }
    }
    accepted.push(("exact_class", "undecided".into()));
    accepted.push(("exact_agrees", "true".into()));
    accepted.push(("exact_agrees", "false".into()));
    // empty when either class is undecided (a sweep writes such rows)
    accepted.push(("exact_agrees", String::new()));
    for w in [-2.0, -1.0, 0.0, 1.0, 3.0] {
        accepted.push(("charmap_winding", format_number(w)));
    }
    for x in [0.0, 0.25, 1.5] {
        accepted.push(("abs_lambda3", format_number(x)));
        accepted.push(("contraction_rate", format_number(x)));
    }
    // a column without a rule takes any number
    accepted.push(("lambda1_re", format_number(-0.25)));
    for (name, bad) in [
        ("class", "indeterminate:standard/bogus"),
        ("class", "indeterminate:bogus/standard"),
        ("class", "indeterminate:standard"),
        ("class", "indeterminate:"),
        ("class", "undecided"),
        ("class", "Standard"),
        ("class", ""),
        ("charmap_verdict", "undecided"),
        ("charmap_verdict", "c2"),
        ("charmap_verdict", ""),
        ("exact_class", "bogus"),
        ("exact_class", ""),
        ("exact_agrees", "yes"),
        ("exact_agrees", "1"),
        ("exact_agrees", "standard"),
        ("charmap_winding", "1.5"),
        ("charmap_winding", "-0.5"),
        ("charmap_winding", "1"),
        ("abs_lambda3", "-0.25"),
        ("contraction_rate", "-1"),
        ("abs_lambda3", "0.250"),
    ] {
        refused.push((name, bad.into()));
    }
    for (name, value) in &accepted {
        assert_eq!(
            verdict(name, value),
            Ok(expected(j as u64)),
            "{name} = {value:?} must be accepted"
        );
    }
    for (name, value) in &refused {
        let e = verdict(name, value).expect_err(&format!("{name} = {value:?} must be refused"));
        assert!(e.contains(name), "{name} = {value:?}: {e}");
    }
}

/// Sweep with enough rows that a block is cut into several pieces
/// (`PIECE_BYTES`), cheap per row (spectral columns only).
const LARGE: &str = r#"
scheme = "nurds"
valences = [3]
[space]
kind = "ratios"
ratio_range = [0.05, 0.95]
[sampler]
kind = "random"
count = 4000
seed = 21
"#;

/// The recheck sample is the `RECHECK_SAMPLE` rows of smallest salted hash
/// (`mix64(salt ^ id)`), whatever way the lines reach the verifier (one at a
/// time, one block cut into parallel pieces, several blocks): a plausible
/// edit of the row of rank 0 or `RECHECK_SAMPLE - 1` is found, one of rank
/// `RECHECK_SAMPLE` or later is not. And the summary rebuilt from the lines
/// is the one accumulated while writing them.
#[test]
fn the_recheck_sample_is_the_bottom_k_of_the_salted_hashes() {
    let plan = Plan::new(SweepSpec::from_toml(LARGE).unwrap());
    let layout = Layout::new(&plan);
    let eval = SpectralEvaluator::new(plan.spec().columns);
    let (lines, written) = data_lines(&plan, &layout);
    let n = lines.len();
    assert!(
        block(&lines).len() > 2 * output::PIECE_BYTES,
        "the block must span several pieces"
    );
    let lambda = layout
        .column_names()
        .iter()
        .position(|c| c == "lambda1_re")
        .unwrap();
    for salt in [0u64, 7, 0xDEAD_BEEF] {
        let mut by_hash: Vec<usize> = (0..n).collect();
        // the verifier's salting of the caller's salt (verify.rs, Verifier::new)
        let salted = mix64(salt ^ 0x005e_ed0f_5ee9);
        by_hash.sort_by_key(|&j| mix64(salted ^ expected(j as u64)));
        for (rank, found) in [
            (0, true),
            (RECHECK_SAMPLE - 1, true),
            (RECHECK_SAMPLE, false),
            (n - 1, false),
        ] {
            let j = by_hash[rank];
            let mut edited = lines.clone();
            let mut cells: Vec<String> = edited[j].split(',').map(str::to_owned).collect();
            let x: f64 = cells[lambda].parse().unwrap();
            cells[lambda] = format_number(x * 0.5);
            edited[j] = cells.join(",");
            let want = if found { Err(lineno(j)) } else { Ok(()) };
            // one line at a time
            let mut v = Verifier::new(&plan, &layout, salt);
            for (k, l) in edited.iter().enumerate() {
                v.check(lineno(k), l, expected(k as u64)).unwrap();
            }
            assert_eq!(
                v.recheck(&eval).map_err(|e| e.0),
                want,
                "salt {salt}, rank {rank}"
            );
            // one block (several pieces), then three blocks
            let mut v = Verifier::new(&plan, &layout, salt);
            v.check_block(lineno(0), &block(&edited), Shard::ALL, n as u64)
                .unwrap();
            assert_eq!(
                v.recheck(&eval).map_err(|e| e.0),
                want,
                "salt {salt}, rank {rank}"
            );
            let mut v = Verifier::new(&plan, &layout, salt);
            for (a, b) in [(0, 1000), (1000, 1001), (1001, n)] {
                v.check_block(lineno(a), &block(&edited[a..b]), Shard::ALL, n as u64)
                    .unwrap();
            }
            assert_eq!(v.rows(), n as u64);
            assert_eq!(
                v.recheck(&eval).map_err(|e| e.0),
                want,
                "salt {salt}, rank {rank}"
            );
        }
    }
    // The summary rebuilt from the unedited lines is the written one.
    let mut v = Verifier::new(&plan, &layout, 1);
    v.check_block(lineno(0), &block(&lines), Shard::ALL, n as u64)
        .unwrap();
    let mut rebuilt = Summary::new(&plan, &layout, Shard::ALL, None);
    v.add_to(&mut rebuilt);
    assert_eq!(rebuilt, written);
}

/// A block whose last line has no `\n` is verified to its end (the tail line counts and is checked), and a
/// line that is not UTF-8 is reported as such at its own line number, after
/// the lines before it, whether it sits in the first piece of a block or in
/// a later one.
#[test]
fn a_last_line_without_newline_is_checked_and_non_utf8_lines_are_located() {
    let plan = Plan::new(SweepSpec::from_toml(SMALL).unwrap());
    let layout = Layout::new(&plan);
    let (lines, _) = data_lines(&plan, &layout);
    let n = lines.len() as u64;
    let mut all = block(&lines);
    assert_eq!(all.pop(), Some(b'\n'));
    let mut v = Verifier::new(&plan, &layout, 1);
    assert_eq!(v.check_block(lineno(0), &all, Shard::ALL, n), Ok(n));
    assert_eq!(v.rows(), n);
    // the tail line is checked: an edit of it is found
    let mut edited = lines.clone();
    let last = edited.len() - 1;
    let cells: Vec<&str> = edited[last].split(',').collect();
    let mut cells: Vec<String> = cells.into_iter().map(str::to_owned).collect();
    let class = layout
        .column_names()
        .iter()
        .position(|c| c == "class")
        .unwrap();
    cells[class] = "bogus".into();
    edited[last] = cells.join(",");
    let mut tail = block(&edited);
    tail.pop();
    let mut v = Verifier::new(&plan, &layout, 1);
    assert!(matches!(
        v.check_block(lineno(0), &tail, Shard::ALL, n),
        Err((l, LineFault::Mismatch(_))) if l == lineno(last)
    ));
    // a byte that is not UTF-8 in row 7 (the rows before it are fine)
    let mut bad = block(&lines);
    let at = block(&lines[..7]).len() + 1;
    bad[at] = 0xff;
    let mut v = Verifier::new(&plan, &layout, 1);
    assert_eq!(
        v.check_block(lineno(0), &bad, Shard::ALL, n),
        Err((lineno(7), LineFault::NotUtf8))
    );
    // in the first line of a block
    let mut bad = block(&lines);
    bad[0] = 0xff;
    let mut v = Verifier::new(&plan, &layout, 1);
    assert_eq!(
        v.check_block(lineno(0), &bad, Shard::ALL, n),
        Err((lineno(0), LineFault::NotUtf8))
    );
    // in a later piece of a block cut into several (and a later block)
    let plan = Plan::new(SweepSpec::from_toml(LARGE).unwrap());
    let layout = Layout::new(&plan);
    let (lines, _) = data_lines(&plan, &layout);
    let n = lines.len();
    assert!(block(&lines).len() > 2 * output::PIECE_BYTES);
    for j in [n / 2, n - 1] {
        let mut bad = block(&lines);
        let at = block(&lines[..j]).len() + 2;
        bad[at] = 0xfe;
        let mut v = Verifier::new(&plan, &layout, 1);
        assert_eq!(
            v.check_block(lineno(0), &bad, Shard::ALL, n as u64),
            Err((lineno(j), LineFault::NotUtf8)),
            "row {j}"
        );
        let mut v = Verifier::new(&plan, &layout, 1);
        v.check_block(
            lineno(0),
            &bad[..block(&lines[..100]).len()],
            Shard::ALL,
            n as u64,
        )
        .unwrap();
        assert_eq!(
            v.check_block(
                lineno(100),
                &bad[block(&lines[..100]).len()..],
                Shard::ALL,
                n as u64
            ),
            Err((lineno(j), LineFault::NotUtf8)),
            "row {j}, second block"
        );
    }
}

/// The summary rebuilt by the verifier counts a failed row under
/// `error` and, in a sweep without a `class` column, every other row under
/// `all` (as `Summary::add` does); a failed row's error text may be quoted.
#[test]
fn rebuilt_summaries_count_failed_rows_and_rows_without_a_class() {
    // no class column
    let spec = SMALL.replace("charmap = true", "classification = false");
    let plan = Plan::new(SweepSpec::from_toml(&spec).unwrap());
    let layout = Layout::new(&plan);
    assert!(!layout.column_names().iter().any(|c| c == "class"));
    let (lines, written) = data_lines(&plan, &layout);
    assert_eq!(written.errors, 0);
    let mut v = Verifier::new(&plan, &layout, 1);
    let n = lines.len() as u64;
    assert_eq!(
        v.check_block(lineno(0), &block(&lines), Shard::ALL, n),
        Ok(n)
    );
    let mut rebuilt = Summary::new(&plan, &layout, Shard::ALL, None);
    v.add_to(&mut rebuilt);
    assert_eq!(rebuilt, written);
    // failed rows (with and without a class column): no results, an error text
    for spec in [SMALL.to_owned(), spec] {
        let plan = Plan::new(SweepSpec::from_toml(&spec).unwrap());
        let layout = Layout::new(&plan);
        let eval = SpectralEvaluator::new(plan.spec().columns);
        let mut want = Summary::new(&plan, &layout, Shard::ALL, None);
        let mut v = Verifier::new(&plan, &layout, 1);
        for id in 0..plan.total() {
            let mut row = layout.row(&plan, &eval, id);
            assert!(row.error.is_none());
            if id % 3 == 1 {
                for c in &mut row.cells[layout.coordinate_cells()..] {
                    *c = subdiv_lab::sweep::Cell::Empty;
                }
                row.error = Some(format!("boom {id}, \"quoted\""));
            }
            want.add(&layout, &row);
            let line = layout.format(&row);
            let line = line.trim_end_matches('\n');
            assert_eq!(line.contains('"'), id % 3 == 1, "{line}");
            assert_eq!(v.check(lineno(id as usize), line, id), Ok(id), "{line}");
        }
        assert_eq!(want.errors, (plan.total() + 1) / 3);
        let mut rebuilt = Summary::new(&plan, &layout, Shard::ALL, None);
        v.add_to(&mut rebuilt);
        assert_eq!(rebuilt, want);
    }
}

/// Only a comma separates fields. A correct line with every comma
/// replaced by a double quote is refused (the quote sends the line to the
/// CSV parser, which sees one malformed field), not split at the quotes.
#[test]
fn quotes_are_not_field_separators() {
    let plan = Plan::new(SweepSpec::from_toml(SMALL).unwrap());
    let layout = Layout::new(&plan);
    let (lines, _) = data_lines(&plan, &layout);
    let mut tried = 0;
    for (j, line) in lines.iter().enumerate() {
        if line.contains('"') {
            continue;
        }
        let mut v = Verifier::new(&plan, &layout, 1);
        assert_eq!(
            v.check(lineno(j), line, expected(j as u64)),
            Ok(expected(j as u64))
        );
        let quoted = line.replace(',', "\"");
        assert!(
            v.check(lineno(j), &quoted, expected(j as u64)).is_err(),
            "{quoted}"
        );
        tried += 1;
    }
    assert!(tried > 0);
}
