//! Headless GPU test of `boulanger`'s BTF pre-computation (issue 9): deterministic, cached on
//! disk and rebuilt when the cache is damaged. It also prints how long the bakes take (issue
//! 9's target: under 10 s for the default patch) — printed, not asserted: tests assert
//! correctness, and a time measured beside other work on two shared cores is not a verdict.
//! Alone in its own test binary so the printed times are not inflated by the other GPU tests
//! (beside them the paper patch's bake measured 16-19 s).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::{Path, PathBuf};
use std::time::Instant;

use grassbench::runner::Harness;
use grassbench_tests::{TEST_SIZE, gpu, render_with, scene};

/// The paper's patch density (21 904 blades a 0.5 m patch): the bake's worst case.
const PAPER_BLADES_PER_M2: f64 = 87_800.0;

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("grassbench-btf-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// The cache files of a folder, sorted by name, with their bytes.
fn files(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut out: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .map(|p| {
            let bytes = std::fs::read(&p).unwrap();
            (p, bytes)
        })
        .collect();
    out.sort();
    out
}

fn with_cache(dir: &str) -> toml::Table {
    let mut t = toml::Table::new();
    t.insert("blades_per_m2".into(), PAPER_BLADES_PER_M2.into());
    t.insert("btf_cache".into(), dir.into());
    t
}

#[test]
fn btf_bake_is_deterministic_cached_and_rebuilt_when_corrupt() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let mut harness = Harness::new(&gpu, scene("football_field_human", 1.0)?, TEST_SIZE, false)?;
    let entry = grassbench_cli::registry::find("boulanger")?;

    // Issue 9: the pre-computation under 10 s here for the default patch. With the default
    // parameters the patch takes the scene's density (meadow: 90 blades/m², 22 blades a
    // patch): creation with the cache off, bake included, measured 0.42 s on lavapipe.
    {
        let defaults = Harness::new(&gpu, scene("meadow", 1.0)?, TEST_SIZE, false)?;
        let started = Instant::now();
        let t = defaults.create(
            entry,
            &toml::Table::from_iter([("btf_cache".into(), "off".into())]),
        )?;
        let seconds = started.elapsed().as_secs_f64();
        eprintln!("measured: creation with the default patch's bake {seconds:.2} s");
        drop(t);
    }
    // The paper's 21 904-blade patch (1 horizontal layer of 512², 40 vertical layers of
    // 256 x 64 and the 128 x 64 shadow mask) is recorded, not bounded: its bake is bound by
    // fill on the two cores, which other engineers' builds share: measured 6.5-6.8 s at a
    // load average of about 5, 11.5-13 s at about 4 with other builds running, 16-19 s
    // beside other tests (issue 9's 10 s is met only when the machine is not busy).
    let started = Instant::now();
    let mut fresh = harness.create(entry, &with_cache("off"))?;
    eprintln!(
        "measured: creation with the paper patch's bake {:.2} s",
        started.elapsed().as_secs_f64()
    );

    // Two bakes into two folders give byte-identical files: the bake is deterministic.
    let (a, b) = (temp_dir("a"), temp_dir("b"));
    let (sa, sb) = (a.to_str().unwrap(), b.to_str().unwrap());
    drop(harness.create(entry, &with_cache(sa))?);
    drop(harness.create(entry, &with_cache(sb))?);
    let (fa, fb) = (files(&a), files(&b));
    assert_eq!(fa.len(), 2, "one file per BTF: {fa:?}");
    for ((pa, da), (pb, db)) in fa.iter().zip(&fb) {
        assert_eq!(pa.file_name(), pb.file_name());
        assert!(da == db, "{}: two bakes differ", pa.display());
    }

    // A third creation loads the files (left untouched) and renders exactly what the fresh
    // bake renders.
    let modified: Vec<_> = fa
        .iter()
        .map(|(p, _)| std::fs::metadata(p).unwrap().modified().unwrap())
        .collect();
    let started = Instant::now();
    let mut loaded = harness.create(entry, &with_cache(sa))?;
    eprintln!(
        "measured: creation from the cache {:.2} s",
        started.elapsed().as_secs_f64()
    );
    for ((p, _), m) in fa.iter().zip(&modified) {
        assert_eq!(
            std::fs::metadata(p)?.modified()?,
            *m,
            "{} rewritten",
            p.display()
        );
    }
    let image_fresh = render_with(&mut harness, fresh.as_mut(), 3)?;
    let image_loaded = render_with(&mut harness, loaded.as_mut(), 3)?;
    assert!(image_fresh == image_loaded, "the cache changes the image");

    // A damaged file (one flipped byte, then a truncated one) is baked again and rewritten,
    // never a panic.
    for damage in [
        &(|d: &mut Vec<u8>| d[5000] ^= 0x40) as &dyn Fn(&mut Vec<u8>),
        &|d: &mut Vec<u8>| d.truncate(100),
    ] {
        for (p, original) in &fa {
            let mut d = original.clone();
            damage(&mut d);
            std::fs::write(p, &d)?;
        }
        drop(harness.create(entry, &with_cache(sa))?);
        for (p, original) in &fa {
            assert!(
                std::fs::read(p)? == *original,
                "{} not rebuilt",
                p.display()
            );
        }
    }
    let _ = std::fs::remove_dir_all(&a);
    let _ = std::fs::remove_dir_all(&b);
    Ok(())
}
