//! The README's command blocks, run and compared with the output they show ([trycmd]).
//!
//! Every ```` ```console ```` block of `README.md` is a transcript: a `$ ltikit …` line is
//! run, the lines after it are its expected stdout and stderr together, `? 1` (or `? 2`) right
//! after the command is its exit code when it is not 0. Output may be elided: `...` on a line
//! of its own skips any number of lines, `[..]` inside a line skips part of that line. Blocks
//! in ```` ```sh ````/```` ```text ```` are not run; each one says why in an HTML comment
//! beside it.
//!
//! The commands never run in the repository: `README.md` is copied to
//! `target/tmp/readme/README.md` with `README.in/` beside it — the fixtures of `tests/readme/`
//! (`tanks.toml`, `u.csv`, `plants.jsonl`) and a copy of `data/plants/` — and an empty
//! `README.out/`, which makes trycmd run the whole file in a fresh temporary directory seeded
//! from `README.in/` (its sandbox) and delete it afterwards, so `-o x.png` writes nowhere
//! that stays. A failure names the copy; its line numbers are those of `README.md`. After the
//! first failing command trycmd skips the rest of the file (they share the sandbox).
//!
//! **Re-blessing** after an intended change of output:
//!
//! ```text
//! TRYCMD=overwrite cargo test --test readme
//! git diff README.md            # review what changed before committing it
//! ```
//!
//! rewrites, in `README.md`, the output of every command that no longer matches (keeping the
//! `...` and `[..]` elisions where it can) and its `? N` line.
//!
//! [trycmd]: https://docs.rs/trycmd

use std::path::{Path, PathBuf};

/// Copies the files of `from` (not recursive: the fixtures are flat) into `to`.
fn copy_files(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let path = entry.unwrap().path();
        if path.is_file() {
            std::fs::copy(&path, to.join(path.file_name().unwrap())).unwrap();
        }
    }
}

/// `cat` on the PATH, to show a fixture's contents; where there is none the `$ cat` lines
/// are skipped.
fn cat() -> trycmd::schema::Bin {
    let path = std::env::var_os("PATH").unwrap_or_default();
    std::env::split_paths(&path)
        .map(|dir| dir.join("cat"))
        .find(|p| p.is_file())
        .map_or(trycmd::schema::Bin::Ignore, trycmd::schema::Bin::Path)
}

#[test]
fn readme_command_blocks() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scratch = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("readme");
    let _ = std::fs::remove_dir_all(&scratch);
    let input = scratch.join("README.in");
    copy_files(&root.join("tests/readme"), &input);
    copy_files(&root.join("data/plants"), &input.join("data/plants"));
    std::fs::create_dir_all(scratch.join("README.out")).unwrap();
    std::fs::write(scratch.join("README.out/.keep"), "").unwrap();
    let readme = scratch.join("README.md");
    std::fs::copy(root.join("README.md"), &readme).unwrap();

    let cases = trycmd::TestCases::new();
    cases
        .register_bin("ltikit", PathBuf::from(env!("CARGO_BIN_EXE_ltikit")))
        .register_bin("cat", cat())
        .timeout(std::time::Duration::from_secs(120))
        .case(&readme);
    let run = std::panic::catch_unwind(|| cases.run());
    // TRYCMD=overwrite rewrote the copy: bring the new output home
    if std::env::var_os("TRYCMD").is_some_and(|m| m == "overwrite") {
        let new = std::fs::read(&readme).unwrap();
        if new != std::fs::read(root.join("README.md")).unwrap() {
            std::fs::write(root.join("README.md"), new).unwrap();
            eprintln!("README.md rewritten: review `git diff README.md`");
        }
    }
    if let Err(panic) = run {
        std::panic::resume_unwind(panic);
    }
}
