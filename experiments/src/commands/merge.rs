//! `grassbench merge`: joins the outputs of sweep shards into one results folder.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use grassbench::runner::write_atomic;

use super::sweep::SweepMeta;

/// Arguments of `merge`.
#[derive(Clone, Debug, clap::Args)]
pub struct MergeArgs {
    /// Shard results folders.
    #[arg(required = true)]
    pub shards: Vec<PathBuf>,
    /// Merged results folder.
    #[arg(long, short)]
    pub out: PathBuf,
    /// Merge shards measured on different adapters or revisions.
    #[arg(long)]
    pub allow_mixed: bool,
    /// Replace a non-empty output folder.
    #[arg(long)]
    pub force: bool,
}

fn read_meta(dir: &Path) -> anyhow::Result<SweepMeta> {
    let path = dir.join("meta.toml");
    let text = std::fs::read_to_string(&path).with_context(|| {
        format!(
            "`{}` is not a sweep results folder (no meta.toml)",
            dir.display()
        )
    })?;
    toml::from_str(&text)
        .with_context(|| format!("`{}` is not a sweep's meta.toml", path.display()))
}

/// Header and records of a CSV file (none when missing).
fn read_csv(path: &Path) -> anyhow::Result<Option<(csv::StringRecord, Vec<csv::StringRecord>)>> {
    if !path.exists() {
        return Ok(None);
    }
    let mut r =
        csv::Reader::from_path(path).with_context(|| format!("reading {}", path.display()))?;
    let headers = r.headers()?.clone();
    let records = r
        .records()
        .collect::<Result<Vec<_>, _>>()
        .with_context(|| format!("reading {}", path.display()))?;
    Ok(Some((headers, records)))
}

/// Merges the shards.
pub fn merge(args: &MergeArgs) -> anyhow::Result<()> {
    let metas = args
        .shards
        .iter()
        .map(|d| read_meta(d))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let first = &metas[0];
    for (dir, m) in args.shards.iter().zip(&metas) {
        if m.sweep_key != first.sweep_key {
            bail!(
                "`{}` holds another sweep (or another version of the file) than `{}`: refusing to merge",
                dir.display(),
                args.shards[0].display()
            );
        }
        if !args.allow_mixed {
            if m.provenance.adapter.name != first.provenance.adapter.name {
                bail!(
                    "`{}` was measured on `{}`, `{}` on `{}`: timings are not comparable; pass --allow-mixed to merge anyway",
                    dir.display(),
                    m.provenance.adapter.name,
                    args.shards[0].display(),
                    first.provenance.adapter.name
                );
            }
            if m.provenance.revision != first.provenance.revision {
                bail!(
                    "`{}` was built from revision {}, `{}` from {}; pass --allow-mixed to merge anyway",
                    dir.display(),
                    m.provenance.revision,
                    args.shards[0].display(),
                    first.provenance.revision
                );
            }
        }
    }
    if std::fs::read_dir(&args.out)
        .map(|mut d| d.next().is_some())
        .unwrap_or(false)
    {
        if !args.force {
            bail!(
                "output folder `{}` is not empty; choose another --out or pass --force",
                args.out.display()
            );
        }
        std::fs::remove_dir_all(&args.out)?;
    }
    for name in ["runs.csv", "frames.csv", "params.csv"] {
        let mut header: Option<csv::StringRecord> = None;
        let mut rows: Vec<csv::StringRecord> = Vec::new();
        let mut seen: HashMap<(String, String), usize> = HashMap::new();
        for dir in &args.shards {
            let Some((h, records)) = read_csv(&dir.join(name))? else {
                continue;
            };
            match &header {
                Some(existing) if existing != &h => bail!(
                    "`{}` has other columns than the first shard's",
                    dir.join(name).display()
                ),
                _ => header = Some(h.clone()),
            }
            let id = h
                .iter()
                .position(|c| c == "run_id")
                .context("no run_id column")?;
            // Rows are keyed by run id plus the row's full text: the same row twice (a shard
            // run twice) is kept once; runs.csv must not hold one run with two results.
            for r in records {
                let run = r.get(id).unwrap_or_default().to_owned();
                let text = r.iter().collect::<Vec<_>>().join(",");
                if name == "runs.csv" {
                    if let Some(&k) = seen.get(&(run.clone(), String::new())) {
                        if rows[k] != r {
                            bail!(
                                "run {run} has different results in two shards; refusing to merge"
                            );
                        }
                        continue;
                    }
                    seen.insert((run, String::new()), rows.len());
                } else if seen.insert((run, text), rows.len()).is_some() {
                    continue;
                }
                rows.push(r);
            }
        }
        let Some(header) = header else { continue };
        let mut w = csv::Writer::from_writer(Vec::new());
        w.write_record(&header)?;
        for r in &rows {
            w.write_record(r)?;
        }
        let bytes = w.into_inner().map_err(|e| anyhow::anyhow!("{e}"))?;
        write_atomic(&args.out.join(name), |f| {
            std::io::Write::write_all(f, &bytes)
        })?;
    }
    for dir in &args.shards {
        if let Ok(entries) = std::fs::read_dir(dir.join("images")) {
            for e in entries.flatten() {
                let to = args.out.join("images").join(e.file_name());
                std::fs::create_dir_all(args.out.join("images"))?;
                std::fs::copy(e.path(), &to)?;
            }
        }
    }
    let merged = SweepMeta {
        shard: format!("merged from {} shards", metas.len()),
        ..read_meta(&args.shards[0])?
    };
    write_atomic(&args.out.join("meta.toml"), |f| {
        std::io::Write::write_all(
            f,
            toml::to_string_pretty(&merged)
                .unwrap_or_default()
                .as_bytes(),
        )
    })?;
    eprintln!("merged {} shards into {}", metas.len(), args.out.display());
    Ok(())
}
