#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]
use grassbench::compare;
use grassbench::runner::Harness;
use grassbench::technique::NoGrass;
use grassbench::wind::WindConfig;
use grassbench_tests::{TEST_SIZE, gpu, scene};

#[test]
fn tune() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let extra: toml::Table = std::env::var("JM").unwrap_or_default().replace(';', "\n").parse()?;
    let reference = grassbench_cli::registry::find("reference")?;
    let jm = grassbench_cli::registry::find("jahrmann")?;
    let scenes: Vec<String> = std::env::var("JM_SCENES").unwrap_or("meadow,football_field,prairie_flyover".into()).split(',').map(String::from).collect();
    for name in &scenes {
        let mut sc = scene(name, 0.25)?;
        for calm in [false, true] {
            if calm { let mut c = sc.config.clone(); c.wind = WindConfig::Calm; sc = grassbench::Scene::from_config(c, sc.base_dir.clone())?; }
            let r = compare::render(&gpu, &sc, reference, &toml::Table::new(), 30, TEST_SIZE)?;
            if let Ok(rp) = std::env::var("JM_REF") {
                let rp: toml::Table = rp.replace(';', "\n").parse()?;
                let r2 = compare::render(&gpu, &sc, reference, &rp, 30, TEST_SIZE)?;
                let s = compare::scores(&r, &r2)?;
                eprintln!("TUNE {name} calm={calm}: reference {rp:?} vs reference FLIP {:.4} p95 {:.4}", s.flip_mean, s.flip_p95);
                continue;
            }
            let mut fin = jm.finest()?; for (k,v) in &extra { fin.insert(k.clone(), v.clone()); }
            let f = compare::render(&gpu, &sc, jm, &fin, 30, TEST_SIZE)?;
            let s = compare::scores(&r, &f)?;
            grassbench::target::save_png(&f, std::path::Path::new(&format!("/tmp/jm/{name}_finest_{calm}.png")))?;
            grassbench::target::save_png(&r, std::path::Path::new(&format!("/tmp/jm/{name}_ref_{calm}.png")))?;
            eprintln!("TUNE {name} calm={calm}: finest vs reference FLIP {:.4} p95 {:.4}", s.flip_mean, s.flip_p95);
            if calm { continue; }
            let d = compare::render(&gpu, &sc, jm, &extra, 30, TEST_SIZE)?;
            grassbench::target::save_png(&d, std::path::Path::new(&format!("/tmp/jm/{name}_default.png")))?;
            let lod = compare::scores(&f, &d)?;
            let bg = { let mut h = Harness::new(&gpu, sc.clone(), TEST_SIZE, false)?; compare::render_in(&mut h, &mut NoGrass, 30)? };
            let pairs = compare::cross_compare(&[("reference".into(), r.clone()), ("jahrmann".into(), d.clone())], &bg)?;
            let p = &pairs[0];
            eprintln!("TUNE {name}: lod FLIP {:.4}; default vs ref FLIP full {:.3} 1/16 {:.3} coverage {:.3} silhouette {:.3}", lod.flip_mean, p.flip_full, p.flip_sixteenth, p.coverage_tile_error, p.silhouette_error);
        }
    }
    Ok(())
}
