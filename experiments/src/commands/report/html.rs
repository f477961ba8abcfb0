//! `report.html` (issue 23 §1): one page per results folder that works offline from disk —
//! its CSS and JavaScript inline, its images by relative paths. Per scene an image viewer
//! (flip, swipe, side by side; zoom and pan; FLIP heat maps where the folder has them), quality
//! against cost with the frontier, the temporal figures; where the time goes; runs.csv as
//! sortable tables.
//!
//! Every string from an input file reaches the page in one of two ways: as JSON inside
//! `<script type="application/json">`, with `<`, `>` and `&` written as `\u003c`, `\u003e`,
//! `\u0026` so no text can close the tag ([`json_for_html`]); or as HTML text through
//! [`escape_html`]. The page's script inserts data with `textContent` only.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use anyhow::Context as _;
use grassbench::runner::{Provenance, write_atomic};
use grassbench::sweep::{REFERENCE, config_id_of, image_path};
use serde::Serialize;

use super::configs::{self, Config, label};
use super::plots::{SPLIT_SEGMENTS, pareto_frontier, split_rows, technique_colors};

/// The page's style sheet.
const CSS: &str = include_str!("html/report.css");
/// The page's script: reads the JSON, builds the viewer, charts and tables.
const JS: &str = include_str!("html/report.js");

/// The file the page is written to, in the results folder.
pub const REPORT_HTML: &str = "report.html";

/// A table as read from a CSV file: its header and rows, every cell as written.
#[derive(Clone, Debug, Default, Serialize)]
pub(super) struct Table {
    /// Where it was read from, relative to the results folder.
    pub(super) name: String,
    /// The header.
    pub(super) columns: Vec<String>,
    /// The rows.
    pub(super) rows: Vec<Vec<String>>,
}

impl Table {
    /// Reads `dir/name` (`None` when the file does not exist).
    fn read(dir: &Path, name: &str) -> anyhow::Result<Option<Self>> {
        let path = dir.join(name);
        if !path.exists() {
            return Ok(None);
        }
        let mut reader = csv::ReaderBuilder::new()
            .flexible(true)
            .from_path(&path)
            .with_context(|| format!("reading {}", path.display()))?;
        let columns = reader
            .headers()
            .with_context(|| format!("reading {}", path.display()))?
            .iter()
            .map(str::to_owned)
            .collect();
        let mut rows = Vec::new();
        for record in reader.records() {
            let record = record.with_context(|| format!("reading {}", path.display()))?;
            rows.push(record.iter().map(str::to_owned).collect());
        }
        Ok(Some(Self {
            name: name.to_owned(),
            columns,
            rows,
        }))
    }

    /// The cell of `row` in column `name` (empty where there is none).
    fn cell<'a>(&'a self, row: &'a [String], name: &str) -> &'a str {
        self.columns
            .iter()
            .position(|c| c == name)
            .and_then(|k| row.get(k))
            .map_or("", String::as_str)
    }
}

/// An image the viewer can show.
#[derive(Clone, Debug, Serialize)]
pub(super) struct ImageEntry {
    /// Its key within the scene.
    pub(super) id: String,
    /// What the viewer calls it.
    pub(super) label: String,
    /// The technique that drew it (`none`: the scene without grass).
    pub(super) technique: String,
    /// Its relative URL (percent-encoded).
    pub(super) src: String,
    /// Its path relative to the results folder.
    #[serde(skip)]
    pub(super) file: String,
}

/// A FLIP heat map between two of a scene's images.
#[derive(Clone, Debug, Serialize)]
pub(super) struct Heatmap {
    /// One image's id.
    pub(super) a: String,
    /// The other's.
    pub(super) b: String,
    /// Its relative URL.
    pub(super) src: String,
}

/// One run in the quality-against-cost chart.
#[derive(Clone, Debug, Serialize)]
pub(super) struct Point {
    /// Its row in runs.csv (0-based, header excluded).
    pub(super) row: usize,
    /// Technique id.
    pub(super) technique: String,
    /// Technique with the parameters that vary.
    pub(super) label: String,
    /// Median GPU wall time, ms.
    pub(super) cost: f64,
    /// Mean FLIP against the reference at 1/4 scale (`None` where there is none).
    pub(super) quality: Option<f64>,
    /// Its image in the viewer.
    pub(super) image: Option<String>,
    /// Figures shown on hover: name, value.
    pub(super) figures: Vec<(String, String)>,
}

/// One scene (with its variant and size) of the page.
#[derive(Clone, Debug, Default, Serialize)]
pub(super) struct ScenePage {
    /// Its heading.
    pub(super) name: String,
    /// Images for the viewer.
    pub(super) images: Vec<ImageEntry>,
    /// Heat maps between them.
    pub(super) heatmaps: Vec<Heatmap>,
    /// The runs with a cost.
    pub(super) points: Vec<Point>,
    /// Indices into `points` on the frontier, cheapest first.
    pub(super) frontier: Vec<usize>,
    /// Failed runs: label and error.
    pub(super) failed: Vec<(String, String)>,
    /// The scene's own tables (compare's temporal, matrix and LOD figures).
    pub(super) tables: Vec<Table>,
}

/// One configuration's "where the time goes" ([`split_rows`]).
#[derive(Clone, Debug, Serialize)]
pub(super) struct SplitEntry {
    /// Scene.
    pub(super) scene: String,
    /// Size.
    pub(super) size: String,
    /// Technique with the parameters that vary.
    pub(super) label: String,
    /// Measured median GPU wall time, ms.
    pub(super) measured_gpu_ms: Option<f64>,
    /// The model's predicted GPU time, ms.
    pub(super) model_ms: f64,
    /// Measured over predicted.
    pub(super) ratio: Option<f64>,
    /// CPU stages and GPU terms, ms, in the order of `segments`.
    pub(super) values: Vec<f64>,
}

/// Everything the page shows, as its script reads it.
#[derive(Clone, Debug, Default, Serialize)]
pub(super) struct Page {
    /// Title (the sweep's name or the folder's).
    pub(super) title: String,
    /// The sweep file's description.
    pub(super) description: String,
    /// Provenance lines.
    pub(super) provenance: Vec<String>,
    /// What the chart's quality axis shows.
    pub(super) quality: String,
    /// Colour per technique.
    pub(super) colors: BTreeMap<String, String>,
    /// runs.csv.
    pub(super) runs: Option<Table>,
    /// Scenes.
    pub(super) scenes: Vec<ScenePage>,
    /// Names of the stacked segments of where the time goes.
    pub(super) segments: Vec<String>,
    /// Where the time goes.
    pub(super) split: Vec<SplitEntry>,
    /// REPORT.md's plots (`plots/*.svg`, where `report` drew them): relative URL, title.
    pub(super) plots: Vec<(String, String)>,
    /// The calibration's coverage checks (`meta.toml`'s unit costs), one row per check and
    /// target; `None` where it has none.
    pub(super) checks: Option<Table>,
}

/// `text` safe as HTML text or a quoted attribute value.
pub(super) fn escape_html(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for ch in text.chars() {
        match ch {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            _ => out.push(ch),
        }
    }
    out
}

/// `value` as JSON that can stand inside a `<script>` element: `<`, `>` and `&` (which JSON
/// only holds inside strings) written as Unicode escapes, so no `</script>` or `<!--` can
/// appear; U+2028 and U+2029 escaped as well.
pub(super) fn json_for_html<T: Serialize>(value: &T) -> anyhow::Result<String> {
    let json = serde_json::to_string(value).context("encoding the report's data as JSON")?;
    Ok(json
        .replace('<', "\\u003c")
        .replace('>', "\\u003e")
        .replace('&', "\\u0026")
        .replace('\u{2028}', "\\u2028")
        .replace('\u{2029}', "\\u2029"))
}

/// A relative path as a URL: every byte but unreserved ones and `/` percent-encoded, so a
/// file name from a results folder can only ever be a relative link to that file.
fn url_path(rel: &str) -> String {
    let mut out = String::with_capacity(rel.len());
    for b in rel.bytes() {
        if b.is_ascii_alphanumeric() || matches!(b, b'-' | b'.' | b'_' | b'~' | b'/') {
            out.push(char::from(b));
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    // A path starting `//` would leave the folder; one starting with `/` too.
    if out.starts_with('/') {
        out.insert(0, '.');
    }
    out
}

/// The whole page.
pub(super) fn render(page: &Page) -> anyhow::Result<String> {
    let data = json_for_html(page)?;
    let mut head = String::new();
    for line in &page.provenance {
        head.push_str(&format!(
            "<p class=\"provenance\">{}</p>\n",
            escape_html(line)
        ));
    }
    if !page.description.is_empty() {
        head.push_str(&format!(
            "<p class=\"description\">{}</p>\n",
            escape_html(&page.description)
        ));
    }
    Ok(format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{title} · grassbench report</title>\n<style>\n{CSS}</style>\n</head>\n<body>\n\
         <header>\n<h1>{title}</h1>\n{head}</header>\n\
         <noscript><p>This report draws its viewer, charts and tables with JavaScript.</p></noscript>\n\
         <nav id=\"toc\"></nav>\n<main id=\"main\"></main>\n\
         <div id=\"tooltip\" class=\"tooltip\" hidden></div>\n\
         <script type=\"application/json\" id=\"grassbench-data\">{data}</script>\n\
         <script>\n{JS}</script>\n</body>\n</html>\n",
        title = escape_html(&page.title),
    ))
}

/// Writes `dir/report.html` from what the folder holds: a sweep's runs.csv, a `run`'s
/// runs.csv and per-scene images, or `compare`'s per-scene images, heat maps and tables.
pub fn write_html(dir: &Path) -> anyhow::Result<()> {
    let page = gather(dir)?;
    let html = render(&page)?;
    let path = dir.join(REPORT_HTML);
    write_atomic(&path, |f| std::io::Write::write_all(f, html.as_bytes()))
        .with_context(|| format!("writing {}", path.display()))?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

/// Whether `dir` holds a sweep's results (runs.csv with run ids, or a sweep's meta.toml), as
/// opposed to a `run`'s (runs.csv without run ids) or `compare`'s (no runs.csv).
pub(super) fn is_sweep_folder(dir: &Path) -> anyhow::Result<bool> {
    match Table::read(dir, "runs.csv")? {
        Some(t) => Ok(t.rows.is_empty()
            || (t.columns.iter().any(|c| c == "run_id")
                && t.rows.iter().all(|r| !t.cell(r, "run_id").is_empty()))),
        None => Ok(std::fs::read_to_string(dir.join("meta.toml"))
            .ok()
            .is_some_and(|t| toml::from_str::<crate::commands::SweepMeta>(&t).is_ok())),
    }
}

/// Reads the folder into the page's data.
pub(super) fn gather(dir: &Path) -> anyhow::Result<Page> {
    let runs = Table::read(dir, "runs.csv")?;
    let sweep = runs.as_ref().is_some_and(|t| {
        !t.rows.is_empty()
            && t.columns.iter().any(|c| c == "run_id")
            && t.rows.iter().all(|r| !t.cell(r, "run_id").is_empty())
    });
    let configs: BTreeMap<String, Config> = match &runs {
        Some(_) if sweep => configs::load(dir)?,
        Some(t) if !t.rows.is_empty() => configs::load_run_folder(dir)?,
        _ => BTreeMap::new(),
    };
    let mut page = Page {
        // The folder as the command named it (`results/default`); a sweep's name replaces it.
        title: dir.display().to_string(),
        segments: SPLIT_SEGMENTS.iter().map(|s| (*s).to_owned()).collect(),
        ..Page::default()
    };
    provenance(dir, &mut page);
    page.checks = checks(dir);
    let all: Vec<&Config> = configs.values().collect();
    page.colors = technique_colors(&all)
        .into_iter()
        .map(|(k, c)| (k, format!("#{:02x}{:02x}{:02x}", c.0, c.1, c.2)))
        .collect();
    let ok: Vec<&Config> = all
        .iter()
        .copied()
        .filter(|c| !c.gpu_wall.is_empty())
        .collect();
    page.split = split_rows(&ok)
        .into_iter()
        .map(|r| SplitEntry {
            scene: r.config.scene.clone(),
            size: r.config.size.clone(),
            label: label(r.config),
            measured_gpu_ms: configs::median(&r.config.gpu_wall),
            model_ms: r.model_ms,
            ratio: configs::median(&r.config.model_ratio),
            values: r.split.to_vec(),
        })
        .collect();
    match &runs {
        Some(t) if !t.rows.is_empty() => {
            page.scenes = scenes_of_runs(dir, t, &configs, sweep)?;
        }
        _ => page.scenes = scenes_of_compare(dir)?,
    }
    if page.scenes.is_empty() {
        anyhow::bail!(
            "`{}` holds neither runs.csv nor scene folders with images: nothing to report",
            dir.display()
        );
    }
    page.quality = if page
        .scenes
        .iter()
        .flat_map(|s| &s.points)
        .any(|p| p.quality.is_some())
    {
        "mean FLIP against the reference at 1/4 scale, last measured frame (runs.csv's \
         flip_vs_reference_quarter; where that is empty, computed by the report from the saved \
         last frames)"
            .into()
    } else {
        "no FLIP: this folder holds no reference frame to compare with".into()
    };
    page.plots = report_plots(dir);
    page.runs = runs;
    Ok(page)
}

/// The SVG plots REPORT.md shows, where they exist, with their titles there.
fn report_plots(dir: &Path) -> Vec<(String, String)> {
    let title = |name: &str| match name {
        "frame_time.svg" => "GPU time per technique and scene".to_owned(),
        "pareto.svg" => "Quality against the reference versus cost".to_owned(),
        "scaling_blades.svg" => "GPU time versus blades".to_owned(),
        "scaling_resolution.svg" => "GPU time versus resolution".to_owned(),
        "time_split.svg" => "Where the time goes".to_owned(),
        other => other.trim_end_matches(".svg").replace('_', " "),
    };
    let mut names: Vec<String> = std::fs::read_dir(dir.join("plots"))
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|e| e.file_name().into_string().ok())
        .filter(|n| n.ends_with(".svg"))
        .collect();
    names.sort();
    names
        .into_iter()
        .map(|n| (url_path(&format!("plots/{n}")), title(&n)))
        .collect()
}

/// Title, description and provenance from meta.toml (a sweep's or a run's).
fn provenance(dir: &Path, page: &mut Page) {
    let Ok(text) = std::fs::read_to_string(dir.join("meta.toml")) else {
        return;
    };
    if let Ok(meta) = toml::from_str::<crate::commands::SweepMeta>(&text) {
        page.title.clone_from(&meta.sweep);
        page.description = toml::from_str::<toml::Table>(&meta.sweep_file)
            .ok()
            .and_then(|t| t.get("description")?.as_str().map(str::to_owned))
            .unwrap_or_default();
        page.provenance = lines(
            &meta
                .provenance
                .to_markdown(&format!("; shard: {}", meta.shard)),
        );
    } else if let Ok(p) = toml::from_str::<Provenance>(&text) {
        page.provenance = lines(&p.to_markdown(""));
    }
}

/// The coverage checks of the unit costs in `dir`'s `meta.toml` as a table (`None` where
/// there are none: no calibration, or one from before the checks).
fn checks(dir: &Path) -> Option<Table> {
    let (_, costs) = crate::commands::recorded_calibration(dir)?;
    let rows: Vec<Vec<String>> = costs
        .iter()
        .flat_map(|c| {
            let target = format!("{}{}", c.size, if c.msaa { " 4xMSAA" } else { "" });
            c.checks.iter().map(move |r| {
                vec![
                    target.clone(),
                    r.check.clone(),
                    format!("{:.0}", r.fragments),
                    format!("{:.0}", r.primitives),
                    r.kept_per_fragment
                        .map_or_else(String::new, |k| format!("{k:.3}")),
                    format!("{:.2}", r.measured_ms),
                    format!("{:.2}", r.predicted_ms),
                    format!("{:.2}", r.ratio),
                ]
            })
        })
        .collect();
    (!rows.is_empty()).then(|| Table {
        name: "meta.toml: the calibration's coverage checks".into(),
        columns: [
            "target",
            "check",
            "fragments",
            "primitives",
            "kept per fragment",
            "measured ms",
            "predicted ms",
            "measured / predicted",
        ]
        .map(str::to_owned)
        .to_vec(),
        rows,
    })
}

/// A Markdown paragraph's lines, its hard breaks and back-ticks dropped.
fn lines(markdown: &str) -> Vec<String> {
    markdown
        .lines()
        .map(|l| l.trim_end().replace('`', ""))
        .filter(|l| !l.is_empty())
        .collect()
}

/// `(technique, frame)` of a `run` image name, `TECHNIQUE_frameNNNN.png`.
fn frame_image(name: &str) -> Option<(&str, u64)> {
    let stem = name.strip_suffix(".png")?;
    let (technique, frame) = stem.rsplit_once("_frame")?;
    Some((technique, frame.parse().ok()?))
}

/// The PNG files of a folder, by name (empty where it does not exist).
fn pngs(dir: &Path) -> BTreeSet<String> {
    std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|e| e.file_name().into_string().ok())
        .filter(|n| n.ends_with(".png"))
        .collect()
}

/// A scene folder's images as `run` and `compare` write them (`run`: every captured frame,
/// `TECHNIQUE_frameNNNN.png`; `compare`: `TECHNIQUE.png`), and compare's heat maps between
/// them, `diff_A_B.png`.
fn scene_folder_images(dir: &Path, scene: &str) -> (Vec<ImageEntry>, Vec<Heatmap>) {
    let files = pngs(&dir.join(scene));
    let mut images = Vec::new();
    let mut frames: Vec<(String, u64, String)> = files
        .iter()
        .filter_map(|n| frame_image(n).map(|(t, f)| (t.to_owned(), f, n.clone())))
        .collect();
    // The reference first, the scene without grass last; each technique's last frame first
    // (the one a run's FLIP compares).
    frames.sort_by_key(|(t, f, _)| {
        (
            t != REFERENCE,
            t == "none",
            t.clone(),
            std::cmp::Reverse(*f),
        )
    });
    for (technique, frame, name) in frames {
        images.push(ImageEntry {
            id: format!("{technique}@{frame}"),
            label: format!("{technique} · frame {frame}"),
            technique,
            src: url_path(&format!("{scene}/{name}")),
            file: format!("{scene}/{name}"),
        });
    }
    let mut plain: Vec<String> = files
        .iter()
        .filter(|n| !n.starts_with("diff_") && !n.starts_with("lod_") && frame_image(n).is_none())
        .filter_map(|n| n.strip_suffix(".png").map(str::to_owned))
        .collect();
    plain.sort_by_key(|t| (t != REFERENCE, t == "none", t.clone()));
    for technique in &plain {
        images.push(ImageEntry {
            id: technique.clone(),
            label: technique.clone(),
            technique: technique.clone(),
            src: url_path(&format!("{scene}/{technique}.png")),
            file: format!("{scene}/{technique}.png"),
        });
    }
    let mut heatmaps = Vec::new();
    for a in &plain {
        for b in &plain {
            let name = format!("diff_{a}_{b}.png");
            if a != b && files.contains(&name) {
                heatmaps.push(Heatmap {
                    a: a.clone(),
                    b: b.clone(),
                    src: url_path(&format!("{scene}/{name}")),
                });
            }
        }
    }
    (images, heatmaps)
}

/// The CSV tables `compare` writes per scene.
fn scene_tables(dir: &Path, scene: &str) -> anyhow::Result<Vec<Table>> {
    let mut out = Vec::new();
    for name in ["temporal.csv", "matrix.csv", "lod.csv"] {
        if let Some(t) = Table::read(dir, &format!("{scene}/{name}"))? {
            out.push(t);
        }
    }
    Ok(out)
}

/// The scenes of a `compare` folder: its sub-folders with images.
fn scenes_of_compare(dir: &Path) -> anyhow::Result<Vec<ScenePage>> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .with_context(|| format!("reading {}", dir.display()))?
        .flatten()
        .filter(|e| e.path().is_dir())
        .filter_map(|e| e.file_name().into_string().ok())
        .collect();
    names.sort();
    let mut scenes = Vec::new();
    for name in names {
        let (images, heatmaps) = scene_folder_images(dir, &name);
        if images.is_empty() {
            continue;
        }
        scenes.push(ScenePage {
            tables: scene_tables(dir, &name)?,
            name,
            images,
            heatmaps,
            ..ScenePage::default()
        });
    }
    Ok(scenes)
}

/// A number cell, if it holds one.
fn number(text: &str) -> Option<f64> {
    text.parse::<f64>().ok().filter(|v| v.is_finite())
}

/// The scenes of a sweep's or a run's runs.csv: per scene (variant, size, MSAA) its images,
/// one chart point per run with a cost, its failed runs.
fn scenes_of_runs(
    dir: &Path,
    runs: &Table,
    configs: &BTreeMap<String, Config>,
    sweep: bool,
) -> anyhow::Result<Vec<ScenePage>> {
    let sizes: BTreeSet<String> = runs
        .rows
        .iter()
        .map(|r| format!("{}x{}", runs.cell(r, "width"), runs.cell(r, "height")))
        .collect();
    let group_name = |r: &[String]| {
        let mut name = runs.cell(r, "scene").to_owned();
        let variant = runs.cell(r, "scene_variant");
        if !variant.is_empty() {
            name = format!("{name} {}", variant.replace(';', " "));
        }
        if sizes.len() > 1 {
            name = format!(
                "{name} {}x{}",
                runs.cell(r, "width"),
                runs.cell(r, "height")
            );
        }
        if runs.cell(r, "msaa") == "true" {
            name.push_str(" 4x MSAA");
        }
        name
    };
    // Labels: a sweep's configurations are keyed by configuration id, a run folder's by
    // scene, size and technique.
    let run_label = |r: &[String]| -> String {
        let key = if sweep {
            config_id_of(runs.cell(r, "run_id")).to_owned()
        } else {
            format!(
                "{}/{}/{}x{}/{}/{}",
                runs.cell(r, "scene"),
                runs.cell(r, "scene_variant"),
                runs.cell(r, "width"),
                runs.cell(r, "height"),
                runs.cell(r, "msaa"),
                runs.cell(r, "technique")
            )
        };
        configs.get(&key).map_or_else(
            || runs.cell(r, "technique").to_owned(),
            // The scene's heading names the variant; the run, its technique and
            // the parameters that vary.
            |c| format!("{} {}", c.technique, c.label).trim().to_owned(),
        )
    };
    let mut order: Vec<String> = Vec::new();
    let mut scenes: BTreeMap<String, ScenePage> = BTreeMap::new();
    // Per scene folder of a run: its images, once.
    let mut folder_images: BTreeMap<String, (Vec<ImageEntry>, Vec<Heatmap>)> = BTreeMap::new();
    for (k, r) in runs.rows.iter().enumerate() {
        let name = group_name(r);
        let scene = runs.cell(r, "scene").to_owned();
        let technique = runs.cell(r, "technique").to_owned();
        if !scenes.contains_key(&name) {
            order.push(name.clone());
            let mut page = ScenePage {
                name: name.clone(),
                ..ScenePage::default()
            };
            if !sweep {
                let (images, heatmaps) = folder_images
                    .entry(scene.clone())
                    .or_insert_with(|| scene_folder_images(dir, &scene))
                    .clone();
                page.images = images;
                page.heatmaps = heatmaps;
                page.tables = scene_tables(dir, &scene)?;
            }
            scenes.insert(name.clone(), page);
        }
        let Some(page) = scenes.get_mut(&name) else {
            continue;
        };
        let label = run_label(r);
        if runs.cell(r, "status") != "ok" {
            page.failed.push((label, runs.cell(r, "error").to_owned()));
            continue;
        }
        // The run's image: a sweep's configuration image, or a run's last captured frame.
        let image = if sweep {
            let config_id = config_id_of(runs.cell(r, "run_id")).to_owned();
            let path = image_path(&config_id);
            if dir.join(&path).exists() && !page.images.iter().any(|i| i.id == config_id) {
                page.images.push(ImageEntry {
                    id: config_id.clone(),
                    label: label.clone(),
                    technique: technique.clone(),
                    src: url_path(&path),
                    file: path.clone(),
                });
            }
            page.images
                .iter()
                .any(|i| i.id == config_id)
                .then_some(config_id)
        } else {
            page.images
                .iter()
                .filter(|i| i.technique == technique)
                .max_by_key(|i| {
                    i.id.rsplit_once('@')
                        .and_then(|(_, f)| f.parse::<u64>().ok())
                })
                .map(|i| i.id.clone())
        };
        let Some(cost) = number(runs.cell(r, "gpu_wall_ms_median")) else {
            page.failed.push((label, "no GPU time measured".into()));
            continue;
        };
        let quality = number(runs.cell(r, "flip_vs_reference_quarter"));
        let mut figures = Vec::new();
        for (name, column) in [
            ("GPU ms (median)", "gpu_wall_ms_median"),
            ("GPU ms p5", "gpu_wall_ms_p5"),
            ("GPU ms p95", "gpu_wall_ms_p95"),
            ("frame ms", "frame_ms_median"),
            ("speed-up", "speedup"),
            ("speed-up 95 % low", "speedup_ci_low"),
            ("speed-up 95 % high", "speedup_ci_high"),
            ("FLIP", "flip_vs_reference"),
            ("FLIP 1/4", "flip_vs_reference_quarter"),
            ("model ms", "model_ms"),
            ("blades drawn", "blades_drawn"),
            ("blades represented", "blades_represented"),
            ("triangles", "triangles"),
            ("repetition", "repetition"),
            ("run", "run_id"),
            ("parameters", "params"),
        ] {
            let v = runs.cell(r, column);
            if !v.is_empty() {
                figures.push((name.to_owned(), v.to_owned()));
            }
        }
        page.points.push(Point {
            row: k,
            technique,
            label,
            cost,
            quality,
            image,
            figures,
        });
    }
    let mut out: Vec<ScenePage> = order
        .into_iter()
        .filter_map(|n| scenes.remove(&n))
        .collect();
    for page in &mut out {
        fill_missing_flip(dir, page);
        let pts: Vec<(usize, (f64, f64))> = page
            .points
            .iter()
            .enumerate()
            .filter_map(|(k, p)| Some((k, (p.cost, p.quality?))))
            .collect();
        let xy: Vec<(f64, f64)> = pts.iter().map(|p| p.1).collect();
        page.frontier = pareto_frontier(&xy).into_iter().map(|k| pts[k].0).collect();
    }
    Ok(out)
}

/// Where runs.csv has no FLIP (a `run` folder: it saves frames but does not compare them),
/// the mean FLIP at 1/4 scale of each run's last saved frame against the reference's same
/// frame, as a sweep measures it.
fn fill_missing_flip(dir: &Path, page: &mut ScenePage) {
    let load = |id: &str| -> Option<image::RgbaImage> {
        let entry = page.images.iter().find(|i| i.id == id)?;
        Some(image::open(dir.join(&entry.file)).ok()?.to_rgba8())
    };
    let Some(reference_id) = page
        .points
        .iter()
        .find(|p| p.technique == REFERENCE)
        .and_then(|p| p.image.clone())
    else {
        return;
    };
    if page.points.iter().all(|p| p.quality.is_some()) {
        return;
    }
    let Some(reference) = load(&reference_id) else {
        return;
    };
    let reference = grassbench::metrics::downsample(&reference, 4);
    let mut computed = Vec::new();
    for (k, p) in page.points.iter().enumerate() {
        if p.quality.is_some() {
            continue;
        }
        let Some(img) = p.image.as_deref().and_then(load) else {
            continue;
        };
        if let Ok(f) =
            grassbench::metrics::flip(&reference, &grassbench::metrics::downsample(&img, 4))
        {
            computed.push((k, f64::from(f.mean)));
        }
    }
    for (k, q) in computed {
        if let Some(p) = page.points.get_mut(k) {
            p.quality = Some(q);
            p.figures.push((
                "FLIP 1/4 (computed by the report)".into(),
                format!("{q:.4}"),
            ));
        }
    }
}

/// Undoes [`url_path`].
#[cfg(test)]
fn percent_decode(text: &str) -> String {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut k = 0;
    while k < bytes.len() {
        if bytes[k] == b'%'
            && let Some(v) = text
                .get(k + 1..k + 3)
                .and_then(|h| u8::from_str_radix(h, 16).ok())
        {
            out.push(v);
            k += 3;
            continue;
        }
        out.push(bytes[k]);
        k += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    const EVIL: &str =
        "</script><script>alert(1)</script><img src=x onerror=alert(2)>&amp;\u{2028}";

    /// The `<script ...>` opening tags and `</script` closings of a page.
    fn script_tags(html: &str) -> (usize, usize) {
        let lower = html.to_ascii_lowercase();
        (
            lower.matches("<script").count(),
            lower.matches("</script").count(),
        )
    }

    #[test]
    fn input_strings_cannot_inject_markup_or_script() {
        let page = Page {
            title: EVIL.into(),
            description: EVIL.into(),
            provenance: vec![EVIL.into()],
            runs: Some(Table {
                name: "runs.csv".into(),
                columns: vec!["scene".into(), "error".into()],
                rows: vec![vec![EVIL.into(), EVIL.into()]],
            }),
            scenes: vec![ScenePage {
                name: EVIL.into(),
                images: vec![ImageEntry {
                    id: EVIL.into(),
                    label: EVIL.into(),
                    technique: EVIL.into(),
                    src: url_path(&format!("{EVIL}/x.png")),
                    file: String::new(),
                }],
                points: vec![Point {
                    row: 0,
                    technique: EVIL.into(),
                    label: EVIL.into(),
                    cost: 1.0,
                    quality: None,
                    image: None,
                    figures: vec![("parameters".into(), format!("segments={EVIL}"))],
                }],
                failed: vec![(EVIL.into(), EVIL.into())],
                ..ScenePage::default()
            }],
            ..Page::default()
        };
        let html = render(&page).unwrap();
        // Exactly the page's own two scripts: the data and the code.
        assert_eq!(script_tags(&html), (2, 2), "{html}");
        assert!(!html.contains("<img"), "markup from the data got through");
        assert!(!html.contains("alert(1)</"), "{html}");
        // The data block holds every string intact once parsed.
        let start = html.find("id=\"grassbench-data\">").unwrap() + "id=\"grassbench-data\">".len();
        let end = start + html[start..].find("</script>").unwrap();
        assert!(!html[start..end].contains('\u{2028}'));
        let parsed: serde_json::Value = serde_json::from_str(&html[start..end]).unwrap();
        assert_eq!(parsed["scenes"][0]["name"], EVIL);
        assert_eq!(parsed["scenes"][0]["failed"][0][1], EVIL);
        assert_eq!(
            parsed["scenes"][0]["points"][0]["figures"][0][1],
            format!("segments={EVIL}")
        );
        assert_eq!(parsed["runs"]["rows"][0][1], EVIL);
        // HTML text: escaped.
        assert!(
            html.contains("<h1>&lt;/script&gt;&lt;script&gt;alert(1)"),
            "{html}"
        );
        // The image path stays a relative file link.
        let src = parsed["scenes"][0]["images"][0]["src"].as_str().unwrap();
        assert!(
            src.bytes()
                .all(|b| b.is_ascii_alphanumeric() || b"-._~/%".contains(&b)),
            "{src}"
        );
        assert!(!src.starts_with('/'));
        // The script never inserts data as markup.
        assert!(!JS.contains("innerHTML") && !JS.contains("outerHTML"));
        assert!(!JS.contains("insertAdjacentHTML") && !JS.contains("document.write"));
        assert!(!JS.to_ascii_lowercase().contains("</script"));
        assert!(!CSS.to_ascii_lowercase().contains("</style"));
    }

    #[test]
    fn the_calibrations_coverage_checks_become_a_table() {
        use grassbench::cost::{FitSummary, Term, UnitCost, UnitCosts, checks::CheckResult};
        let dir =
            std::env::temp_dir().join(format!("grassbench-html-checks-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let costs = |msaa| UnitCosts {
            msaa,
            checks: vec![CheckResult {
                check: "slivers_blended".into(),
                fragments: 1000.0,
                primitives: 90.0,
                kept_per_fragment: Some(0.086),
                measured_ms: 3.0,
                predicted_ms: 2.0,
                ratio: 1.5,
            }],
            ..UnitCosts::from_ms_per_unit(
                "320x180".into(),
                "test".into(),
                [UnitCost {
                    value: 1e-6,
                    standard_error: 0.0,
                    at_zero: false,
                }; Term::ALL.len()],
                FitSummary::default(),
            )
        };
        #[derive(serde::Serialize)]
        struct Meta {
            unit_costs: Vec<UnitCosts>,
        }
        let meta = Meta {
            unit_costs: vec![costs(false), costs(true)],
        };
        std::fs::write(dir.join("meta.toml"), toml::to_string(&meta).unwrap()).unwrap();
        let t = checks(&dir).expect("a table");
        assert_eq!(t.rows.len(), 2);
        assert_eq!(
            t.rows[1],
            [
                "320x180 4xMSAA",
                "slivers_blended",
                "1000",
                "90",
                "0.086",
                "3.00",
                "2.00",
                "1.50"
            ]
        );
        // No unit costs, or none with checks: no table.
        std::fs::write(dir.join("meta.toml"), "").unwrap();
        assert!(checks(&dir).is_none());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn escapes_round_trip() {
        assert_eq!(escape_html("a<b>&\"'"), "a&lt;b&gt;&amp;&quot;&#39;");
        assert_eq!(
            json_for_html(&"</script>").unwrap(),
            "\"\\u003c/script\\u003e\""
        );
        for p in ["meadow/zhang_frame0003.png", "a b/<x>.png", "ü/%.png"] {
            assert_eq!(percent_decode(&url_path(p)), p);
        }
        // A leading slash stays inside the folder; a scheme is no scheme.
        assert_eq!(url_path("/etc/passwd"), "./etc/passwd");
        assert_eq!(url_path("//host/x"), ".//host/x");
        assert_eq!(url_path("javascript:alert(1)"), "javascript%3Aalert%281%29");
        assert_eq!(frame_image("none_frame0022.png"), Some(("none", 22)));
        assert_eq!(frame_image("diff_a_b.png"), None);
    }
}
