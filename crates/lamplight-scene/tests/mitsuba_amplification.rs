//! Nested amplification shapes for the Mitsuba reader, generated over a grid
//! of sizes (the in-suite counterpart of the `mitsuba_includes` fuzz target):
//! chains of `<default>`s that each repeat the last `k` times, and files that
//! each include the next `k` times, `depth` deep. Each either reads (when its
//! size stays under the budgets) or ends in the one error of the budget it
//! crosses, and every case ends within issue 30's bound of 5 seconds (each
//! takes milliseconds; the bound catches a budget that stopped bounding,
//! where a tighter one failed under a loaded 2-core machine's test run).
//! See: issue 30 in the project's tracker.

use std::path::Path;
use std::time::{Duration, Instant};

use lamplight_scene::formats::mitsuba::{self, xml};

fn scene(body: &str) -> String {
    format!("<scene version=\"3.0.0\">\n{body}\n<sensor type=\"perspective\"/>\n</scene>\n")
}

/// Reads `text` as `dir/main.xml`; the error's message, if any, and the time taken.
fn read(dir: &Path, text: String) -> (Result<(), String>, Duration) {
    let start = Instant::now();
    let result = mitsuba::parse_table(&dir.join("main.xml"), text, &[]).map(drop).map_err(|e| e.to_string());
    (result, start.elapsed())
}

#[test]
fn amplification_shapes_stay_bounded() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut cases = 0;
    // Defaults: a0 = "xx", a(n) = a(n-1) repeated k times; the last is used.
    for k in 2..=6u32 {
        for n in 1..=40u32 {
            let mut lines = vec!["<default name=\"a0\" value=\"xx\"/>".to_string()];
            for i in 1..=n {
                lines.push(format!("<default name=\"a{i}\" value=\"{}\"/>", format!("$a{}", i - 1).repeat(k as usize)));
            }
            lines.push(format!("<bsdf type=\"diffuse\" id=\"b\"><string name=\"s\" value=\"$a{n}\"/></bsdf>"));
            let (result, took) = read(d, scene(&lines.join("\n")));
            assert!(took < Duration::from_secs(5), "k={k} n={n}: {took:?}");
            // Bytes made: every default's value, 2 k^i for i = 1..=n, and the use of the last.
            let sizes: Vec<u64> = (1..=n).map(|i| u64::from(k).saturating_pow(i).saturating_mul(2)).collect();
            let largest = *sizes.last().unwrap();
            let total: u64 = sizes.iter().fold(largest, |t, &s| t.saturating_add(s));
            match result {
                Ok(()) => assert!(largest <= xml::MAX_VALUE_BYTES && total <= xml::MAX_SUBSTITUTED_BYTES, "k={k} n={n} read"),
                Err(e) => {
                    assert!(largest > xml::MAX_VALUE_BYTES || total > xml::MAX_SUBSTITUTED_BYTES, "k={k} n={n}: {e}");
                    assert!(e.contains("substituting the $names would make"), "k={k} n={n}: {e}");
                }
            }
            cases += 1;
        }
    }
    // Includes: f0 includes f1 k times, ..., f(depth-1) includes f(depth).
    for k in 1..=6usize {
        for depth in 1..=12usize {
            let sub = d.join(format!("fan-{k}-{depth}"));
            std::fs::create_dir_all(&sub).unwrap();
            for i in 0..depth {
                let body = format!("<include filename=\"f{}.xml\"/>\n", i + 1).repeat(k);
                std::fs::write(sub.join(format!("f{i}.xml")), format!("<scene version=\"3.0.0\">\n{body}</scene>\n")).unwrap();
            }
            std::fs::write(sub.join(format!("f{depth}.xml")), "<scene version=\"3.0.0\"><bsdf type=\"diffuse\"/></scene>\n").unwrap();
            let start = Instant::now();
            let main = sub.join("main.xml");
            let result = mitsuba::parse_table(&main, scene("<include filename=\"f0.xml\"/>"), &[]).map(drop).map_err(|e| e.to_string());
            assert!(start.elapsed() < Duration::from_secs(5), "k={k} depth={depth}: {:?}", start.elapsed());
            // Includes read: 1 + k + k^2 + ... + k^depth.
            let includes: u64 = (0..=depth as u32).map(|i| (k as u64).pow(i)).sum();
            let too_deep = depth + 1 > xml::MAX_INCLUDE_DEPTH;
            match result {
                Ok(()) => assert!(includes <= xml::MAX_INCLUDES as u64 && !too_deep, "k={k} depth={depth} read"),
                Err(e) => assert!(
                    (includes > xml::MAX_INCLUDES as u64 && e.contains("more than 1024 includes in one scene")) || too_deep,
                    "k={k} depth={depth}: {e}"
                ),
            }
            cases += 1;
        }
    }
    assert_eq!(cases, 5 * 40 + 6 * 12);
}
