//! `report.html` in a real browser (issue 23 §2): headless Chromium loads the page a tiny
//! sweep (and a tiny `run` and `compare`) wrote, and the page's own `?selftest=1` checks that a
//! keystroke flips the image viewer (and another lays a heat map over it where there is one),
//! that hovering and clicking a chart point work, that the charts hold one point per run and
//! that a header click sorts, and collects every error (`window.onerror`, `console.error`, an image that did not
//! load) into `<html data-selftest>`, which these tests read from the dumped DOM. Broken
//! copies of the page show the check can fail. Needs Chromium: `bash .ci/install-deps`
//! installs it (`make test` runs that first).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::Context as _;

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "grassbench-report-html-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn grassbench(args: &[&str]) -> anyhow::Result<String> {
    let out = Command::new(env!("CARGO_BIN_EXE_grassbench"))
        .args(args)
        .output()
        .context("starting grassbench")?;
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    anyhow::ensure!(out.status.success(), "grassbench {args:?} failed:\n{err}");
    Ok(err)
}

/// The Chromium binary, or a failure that says how to install it (never a silent skip).
fn chromium() -> PathBuf {
    for name in ["chromium", "chromium-browser", "google-chrome"] {
        if let Some(path) = std::env::var_os("PATH").and_then(|paths| {
            std::env::split_paths(&paths)
                .map(|d| d.join(name))
                .find(|p| p.is_file())
        }) {
            return path;
        }
    }
    panic!(
        "Chromium is not installed, and the report's browser test needs it: run `bash .ci/install-deps` \
         (it installs Debian's `chromium`; `make test` runs it first)"
    );
}

/// What the page's self-test wrote: `data-selftest` and `data-points` of `<html>`.
struct Outcome {
    selftest: String,
    points: Option<usize>,
}

/// An attribute of the dumped DOM's `<html>` start tag.
fn html_attribute(dom: &str, name: &str) -> Option<String> {
    let start = dom.find("<html")?;
    let head = start + dom[start..].find("<head")?;
    let tag = &dom[start..head];
    let key = format!("{name}=\"");
    let from = tag.find(&key)? + key.len();
    let to = from + tag[from..].find('"')?;
    Some(
        tag[from..to]
            .replace("&gt;", ">")
            .replace("&lt;", "<")
            .replace("&quot;", "\"")
            .replace("&amp;", "&"),
    )
}

/// Loads `page` with `?selftest=1` in headless Chromium and reads the outcome.
fn selftest(page: &Path) -> Outcome {
    let profile = tempdir_for(page);
    let url = format!("file://{}?selftest=1", page.display());
    let out = Command::new(chromium())
        .args([
            "--headless=new",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
            "--allow-file-access-from-files",
            "--virtual-time-budget=8000",
            &format!("--user-data-dir={}", profile.display()),
            "--dump-dom",
            &url,
        ])
        .output()
        .expect("chromium runs");
    let _ = std::fs::remove_dir_all(&profile);
    let dom = String::from_utf8_lossy(&out.stdout).into_owned();
    let selftest = html_attribute(&dom, "data-selftest").unwrap_or_else(|| {
        panic!(
            "the page wrote no data-selftest (its script did not finish); chromium said:\n{}\nDOM head:\n{}",
            String::from_utf8_lossy(&out.stderr),
            dom.chars().take(2000).collect::<String>()
        )
    });
    Outcome {
        points: html_attribute(&dom, "data-points").and_then(|p| p.parse().ok()),
        selftest,
    }
}

/// A fresh Chromium profile folder beside `page` (tests run in parallel).
fn tempdir_for(page: &Path) -> PathBuf {
    let d = page.with_extension("profile");
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Rows of a CSV file (header excluded).
fn rows(path: &Path) -> usize {
    csv::Reader::from_path(path).unwrap().records().count()
}

/// Checks a generated report in the browser, then that broken copies of it are caught.
fn check_page(dir: &Path) {
    let page = dir.join("report.html");
    let html = std::fs::read_to_string(&page).unwrap();
    let runs = rows(&dir.join("runs.csv"));
    let outcome = selftest(&page);
    assert!(
        outcome.selftest.starts_with("ok:"),
        "{}: {}",
        page.display(),
        outcome.selftest
    );
    assert_eq!(
        outcome.points,
        Some(runs),
        "one chart point per row of runs.csv: {}",
        outcome.selftest
    );

    // A viewer whose flip does nothing is reported.
    let flip = "this.showing = this.showing === 'a' ? 'b' : 'a';";
    assert!(
        html.contains(flip),
        "the page's flip changed: update this test"
    );
    let broken = dir.join("report-broken-flip.html");
    std::fs::write(&broken, html.replace(flip, "")).unwrap();
    let outcome = selftest(&broken);
    assert!(
        outcome.selftest.starts_with("fail:") && outcome.selftest.contains("did not flip"),
        "a broken flip passed: {}",
        outcome.selftest
    );

    // An error on the console is reported.
    let marker = "'use strict';";
    let broken = dir.join("report-console-error.html");
    std::fs::write(
        &broken,
        html.replacen(
            marker,
            "'use strict'; setTimeout(() => console.error('injected failure'), 0);",
            1,
        ),
    )
    .unwrap();
    let outcome = selftest(&broken);
    assert!(
        outcome.selftest.starts_with("fail:") && outcome.selftest.contains("injected failure"),
        "a console error passed: {}",
        outcome.selftest
    );

    // A chart that lost a point is reported.
    let point = "circles.push(c);\n      s.append(c);";
    assert!(
        html.contains(point),
        "the page's points changed: update this test"
    );
    let broken = dir.join("report-lost-point.html");
    std::fs::write(
        &broken,
        html.replace(point, "circles.push(c);\n      if (k > 0) s.append(c);"),
    )
    .unwrap();
    let outcome = selftest(&broken);
    assert!(
        outcome.selftest.starts_with("fail:") && outcome.selftest.contains("points for"),
        "a lost point passed: {}",
        outcome.selftest
    );
}

/// A tiny sweep (320x180, two measured frames, two techniques and the reference) writes
/// report.html; it works in the browser, and so does the one `grassbench report` rewrites
/// after script and markup were planted in runs.csv's parameters and error cells.
#[test]
fn a_sweeps_report_html_works_in_a_browser() {
    chromium();
    let dir = temp("sweep");
    let file = dir.join("tiny.toml");
    std::fs::write(
        &file,
        "name = \"tiny_html\"\ndescription = \"report.html <b>browser</b> test\"\n\
         scenes = [\"meadow\"]\ntechniques = [\"reference\", \"zhang\", \"perbet\"]\n\
         resolutions = [\"320x180\"]\nrepetitions = 1\nwarmup = 1\nframes = 2\n\
         [scene_params]\n\"grass.density\" = [3.0]\n\"terrain.size\" = [[20.0, 20.0]]\n",
    )
    .unwrap();
    let out = dir.join("results");
    grassbench(&["sweep", file.to_str().unwrap(), "-o", out.to_str().unwrap()]).unwrap();
    assert_eq!(rows(&out.join("runs.csv")), 3);
    check_page(&out);
    // The sweep calibrated, and its page holds the calibration's coverage checks.
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(html.contains("meta.toml: the calibration's coverage checks"));

    // Plant markup and script in text cells of runs.csv: the page must show them as text.
    let path = out.join("runs.csv");
    let mut reader = csv::Reader::from_path(&path).unwrap();
    let headers = reader.headers().unwrap().clone();
    let records: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    let params = headers.iter().position(|h| h == "params").unwrap();
    let error = headers.iter().position(|h| h == "error").unwrap();
    let mut writer = csv::Writer::from_path(&path).unwrap();
    writer.write_record(&headers).unwrap();
    for (k, record) in records.iter().enumerate() {
        let fields: Vec<String> = record
            .iter()
            .enumerate()
            .map(|(j, v)| {
                if k == 1 && j == params {
                    format!(
                        "{v};x=<img src=nowhere onerror=\"document.documentElement.setAttribute('data-pwned','img')\">"
                    )
                } else if k == 1 && j == error {
                    "</script><script>document.documentElement.setAttribute('data-pwned','script')</script>".into()
                } else {
                    v.to_owned()
                }
            })
            .collect();
        writer.write_record(&fields).unwrap();
    }
    writer.flush().unwrap();
    drop(writer);
    grassbench(&["report", out.to_str().unwrap()]).unwrap();
    assert!(out.join("REPORT.md").exists());
    let page = out.join("report.html");
    let outcome = selftest(&page);
    assert!(
        outcome.selftest.starts_with("ok:"),
        "after planting markup: {}",
        outcome.selftest
    );
    let dom_attr = html_attribute(
        &String::from_utf8_lossy(
            &Command::new(chromium())
                .args([
                    "--headless=new",
                    "--no-sandbox",
                    "--disable-gpu",
                    "--virtual-time-budget=5000",
                    &format!("--user-data-dir={}", tempdir_for(&page).display()),
                    "--dump-dom",
                    &format!("file://{}", page.display()),
                ])
                .output()
                .unwrap()
                .stdout,
        ),
        "data-pwned",
    );
    assert_eq!(dom_attr, None, "planted script ran");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `grassbench run` writes report.html too; it works in the browser.
#[test]
fn a_runs_report_html_works_in_a_browser() {
    chromium();
    let dir = temp("run");
    let out = dir.join("results");
    grassbench(&[
        "run",
        "-t",
        "reference,perbet",
        "-s",
        "football_field",
        "--frames",
        "2",
        "--warmup",
        "1",
        "--size",
        "160x90",
        "--no-calibration",
        "-o",
        out.to_str().unwrap(),
    ])
    .unwrap();
    check_page(&out);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `grassbench compare` writes report.html too: its viewer lays the FLIP heat map of a pair
/// over the images (key `h`), and the temporal figures are there.
#[test]
fn a_compares_report_html_shows_heat_maps() {
    chromium();
    let dir = temp("compare");
    let out = dir.join("results");
    grassbench(&[
        "compare",
        "-t",
        "reference,perbet",
        "-s",
        "football_field",
        "--size",
        "96x54",
        "--motion-frames",
        "2",
        "-o",
        out.to_str().unwrap(),
    ])
    .unwrap();
    let page = out.join("report.html");
    let outcome = selftest(&page);
    assert!(
        outcome.selftest.starts_with("ok:") && outcome.selftest.contains("heat map"),
        "{}",
        outcome.selftest
    );
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(
        html.contains("football_field/temporal.csv"),
        "no temporal table"
    );
    // With the heat map gone, the page says so instead of showing nothing.
    std::fs::remove_file(out.join("football_field/diff_reference_perbet.png")).unwrap();
    grassbench(&["report", out.to_str().unwrap()]).unwrap();
    let outcome = selftest(&page);
    assert!(
        outcome.selftest.starts_with("ok:") && !outcome.selftest.contains("heat map"),
        "{}",
        outcome.selftest
    );
    let dom = String::from_utf8_lossy(
        &Command::new(chromium())
            .args([
                "--headless=new",
                "--no-sandbox",
                "--disable-gpu",
                "--virtual-time-budget=5000",
                &format!("--user-data-dir={}", tempdir_for(&page).display()),
                "--dump-dom",
                &format!("file://{}", page.display()),
            ])
            .output()
            .unwrap()
            .stdout,
    )
    .into_owned();
    assert!(
        dom.contains("No FLIP heat map for reference against perbet"),
        "no note"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
