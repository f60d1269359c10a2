use std::path::PathBuf;
use std::process::ExitCode;

use rslam_core::dataset::verify_output;

#[derive(clap::Args)]
pub struct VerifyArgs {
    /// A dataset or image folder that rslam wrote (it has rslam.json and rslam.b3sum).
    dir: PathBuf,
}

/// Exit 0 when every file matches the checksums the manifest's digest stands for, 1 otherwise.
pub fn run(args: VerifyArgs) -> anyhow::Result<ExitCode> {
    let verdict = verify_output(&args.dir)?;
    for line in verdict.problems() {
        println!("{line}");
    }
    if verdict.is_ok() {
        println!(
            "{}: ok, {} files match digest {}",
            args.dir.display(),
            verdict.files,
            verdict.digest
        );
        Ok(ExitCode::SUCCESS)
    } else {
        println!("{}: FAILED", args.dir.display());
        Ok(ExitCode::from(1))
    }
}
