//! The output folder of a command that writes a fresh set of results (`run`, `compare`,
//! `merge`): new results are never mixed into an old folder's, except that `run` and `compare`
//! resume their own unfinished output ([`Progress`]).

use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};

/// Creates `dir`, refusing a non-empty one unless `force`, which empties it first.
pub fn prepare_out_dir(dir: &Path, force: bool) -> anyhow::Result<()> {
    let non_empty = std::fs::read_dir(dir)
        .map(|mut d| d.next().is_some())
        .unwrap_or(false);
    if non_empty {
        if !force {
            bail!(
                "output folder `{}` is not empty; choose another --out or pass --force to replace it",
                dir.display()
            );
        }
        std::fs::remove_dir_all(dir)
            .with_context(|| format!("cannot clear `{}`", dir.display()))?;
    }
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create `{}`", dir.display()))
}

/// The manifest a resumable command (`run`, `compare`) keeps in its output folder: the
/// command, the arguments that shape its results, its scenes and which of them are finished.
pub const PROGRESS_FILE: &str = ".grassbench-progress.toml";

/// What [`PROGRESS_FILE`] holds.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
struct Manifest {
    /// The command (`run`, `compare`).
    command: String,
    /// Every argument that shapes the results, resolved (`--technique` as the ids it selects),
    /// by its flag.
    arguments: std::collections::BTreeMap<String, String>,
    /// Whether every scene and the folder's own files are written.
    finished: bool,
    /// The scenes whose folders are complete, in the order they finished.
    #[serde(default)]
    done: Vec<DoneScene>,
}

/// A scene whose folder is complete.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct DoneScene {
    /// The scene's name (its folder).
    pub scene: String,
    /// What failed on it (`technique on scene: error`), reported again at the end of a resumed
    /// command as at the end of an uninterrupted one.
    #[serde(default)]
    pub failures: Vec<String>,
}

/// A resumable command's output folder: a fresh one, or an unfinished one of the same command
/// and arguments, whose finished scenes are kept (see [`Progress::open`]).
pub struct Progress {
    path: PathBuf,
    manifest: Manifest,
    resumed: bool,
}

impl Progress {
    /// Opens `dir` for `command` with `arguments` (flag → resolved value) over `scenes`.
    ///
    /// An empty or missing folder starts fresh, and so does any folder with `force` (emptied
    /// first). A folder holding an unfinished output of the same command and arguments is
    /// resumed: its finished scenes' folders are kept, everything else but `meta.toml` is
    /// removed (unfinished scenes are redone from scratch), and "resuming: N of M scenes
    /// already done" goes to stderr. Any other non-empty folder (another command's output,
    /// other arguments', a finished one, or files grassbench did not write) is refused with
    /// the difference and the fix.
    pub fn open(
        dir: &Path,
        force: bool,
        command: &str,
        arguments: std::collections::BTreeMap<String, String>,
        scenes: &[String],
    ) -> anyhow::Result<Self> {
        let path = dir.join(PROGRESS_FILE);
        let fresh = Manifest {
            command: command.to_owned(),
            arguments,
            finished: false,
            done: Vec::new(),
        };
        let non_empty = std::fs::read_dir(dir)
            .map(|mut d| d.next().is_some())
            .unwrap_or(false);
        if non_empty && !force {
            let old = std::fs::read_to_string(&path)
                .ok()
                .and_then(|t| toml::from_str::<Manifest>(&t).ok());
            let Some(mut old) = old else {
                bail!(
                    "output folder `{}` is not empty and holds no unfinished grassbench {command}; choose another --out or pass --force to replace it",
                    dir.display()
                );
            };
            let differences = differences(&old, &fresh);
            if old.finished || !differences.is_empty() {
                let state = if old.finished {
                    "a finished"
                } else {
                    "an unfinished"
                };
                let what = if differences.is_empty() {
                    "with the same arguments".to_owned()
                } else {
                    format!("with other arguments: {}", differences.join(", "))
                };
                let resume = if old.finished {
                    ""
                } else {
                    "run its own command to resume it, "
                };
                bail!(
                    "output folder `{}` is not empty: it holds {state} `grassbench {}` {what}; {resume}choose another --out or pass --force to replace it",
                    dir.display(),
                    old.command
                );
            }
            old.done.retain(|d| scenes.contains(&d.scene));
            let keep: Vec<std::ffi::OsString> = old
                .done
                .iter()
                .map(|d| d.scene.clone().into())
                .chain([PROGRESS_FILE.into(), "meta.toml".into()])
                .collect();
            for entry in std::fs::read_dir(dir)
                .with_context(|| format!("cannot read `{}`", dir.display()))?
            {
                let entry = entry.with_context(|| format!("cannot read `{}`", dir.display()))?;
                if keep.contains(&entry.file_name()) {
                    continue;
                }
                let p = entry.path();
                if p.is_dir() {
                    std::fs::remove_dir_all(&p)
                } else {
                    std::fs::remove_file(&p)
                }
                .with_context(|| format!("cannot remove unfinished `{}`", p.display()))?;
            }
            eprintln!(
                "resuming: {} of {} scenes already done in `{}`",
                old.done.len(),
                scenes.len(),
                dir.display()
            );
            let progress = Self {
                path,
                manifest: old,
                resumed: true,
            };
            progress.save()?;
            return Ok(progress);
        }
        prepare_out_dir(dir, force)?;
        let progress = Self {
            path,
            manifest: fresh,
            resumed: false,
        };
        progress.save()?;
        Ok(progress)
    }

    /// Whether this folder was resumed rather than started fresh.
    pub fn resumed(&self) -> bool {
        self.resumed
    }

    /// `scene`'s record where its folder is complete.
    pub fn done(&self, scene: &str) -> Option<&DoneScene> {
        self.manifest.done.iter().find(|d| d.scene == scene)
    }

    /// Records `scene`'s folder as complete, with what failed on it; call once its last file
    /// is written.
    pub fn scene_done(&mut self, scene: &str, failures: Vec<String>) -> anyhow::Result<()> {
        self.manifest.done.retain(|d| d.scene != scene);
        self.manifest.done.push(DoneScene {
            scene: scene.to_owned(),
            failures,
        });
        self.save()
    }

    /// Records the folder as finished (every scene and the summary files written): the same
    /// command is then refused rather than resumed.
    pub fn finish(&mut self) -> anyhow::Result<()> {
        self.manifest.finished = true;
        self.save()
    }

    fn save(&self) -> anyhow::Result<()> {
        let text = toml::to_string_pretty(&self.manifest)?;
        grassbench::runner::write_atomic(&self.path, |f| {
            std::io::Write::write_all(f, text.as_bytes())
        })
        .with_context(|| format!("writing {}", self.path.display()))
    }
}

/// How `new` differs from `old`, argument by argument (`--frames is 4 there, 5 here`).
fn differences(old: &Manifest, new: &Manifest) -> Vec<String> {
    if old.command != new.command {
        return vec![format!(
            "it is a `{}`, not a `{}`",
            old.command, new.command
        )];
    }
    let mut keys: Vec<&String> = old.arguments.keys().chain(new.arguments.keys()).collect();
    keys.sort();
    keys.dedup();
    let shown = |v: Option<&String>| v.map_or("unset".to_owned(), |v| format!("`{v}`"));
    keys.into_iter()
        .filter(|k| old.arguments.get(*k) != new.arguments.get(*k))
        .map(|k| {
            format!(
                "{k} is {} there, {} here",
                shown(old.arguments.get(k)),
                shown(new.arguments.get(k))
            )
        })
        .collect()
}

/// The manifest arguments every command shares: its techniques and scenes by name, in the
/// order it runs them (each command adds its own).
pub fn selection_arguments(
    entries: &[&grassbench::technique::TechniqueEntry],
    scene_names: &[String],
) -> std::collections::BTreeMap<String, String> {
    std::collections::BTreeMap::from([
        (
            "--technique".to_owned(),
            entries
                .iter()
                .map(|e| e.info.id)
                .collect::<Vec<_>>()
                .join(","),
        ),
        ("--scene".to_owned(), scene_names.join(",")),
    ])
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::*;

    fn args(frames: &str) -> BTreeMap<String, String> {
        BTreeMap::from([
            ("--frames".to_owned(), frames.to_owned()),
            ("--scene".to_owned(), "a,b".to_owned()),
        ])
    }

    #[test]
    fn resumes_the_same_arguments_and_refuses_others() -> anyhow::Result<()> {
        let dir = std::env::temp_dir().join(format!("grassbench-progress-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let scenes = ["a".to_owned(), "b".to_owned()];
        let mut p = Progress::open(&dir, false, "run", args("4"), &scenes)?;
        assert!(!p.resumed());
        std::fs::create_dir_all(dir.join("a"))?;
        std::fs::write(dir.join("a/runs.csv"), "x")?;
        p.scene_done("a", vec!["t on a: boom".into()])?;
        std::fs::create_dir_all(dir.join("b"))?;
        std::fs::write(dir.join("b/half.png"), "x")?;
        std::fs::write(dir.join("runs.csv"), "x")?;

        let e = Progress::open(&dir, false, "run", args("5"), &scenes)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(e.contains("--frames is `4` there, `5` here"), "{e}");
        let e = Progress::open(&dir, false, "compare", args("4"), &scenes)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(e.contains("not a `compare`"), "{e}");

        let p = Progress::open(&dir, false, "run", args("4"), &scenes)?;
        assert!(p.resumed());
        assert_eq!(
            p.done("a").map(|d| d.failures.clone()),
            Some(vec!["t on a: boom".to_owned()])
        );
        assert!(p.done("b").is_none());
        assert!(dir.join("a/runs.csv").exists());
        assert!(!dir.join("b").exists() && !dir.join("runs.csv").exists());

        let mut p = p;
        p.finish()?;
        let e = Progress::open(&dir, false, "run", args("4"), &scenes)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            e.contains("not empty") && e.contains("finished") && e.contains("--force"),
            "{e}"
        );
        let p = Progress::open(&dir, true, "run", args("4"), &scenes)?;
        assert!(!p.resumed() && !dir.join("a").exists());
        std::fs::remove_dir_all(&dir)?;
        Ok(())
    }
}
