//! Every catalogue entry's GPU pass against its CPU twin, as one table-driven test (as wgpu's
//! example tests run one harness over a table of examples). Each entry is built once, like the
//! `Perturber` builds it, and applied at several severities, seeds and frames (and its explicit
//! form, where it has one) to the shared test image and depth; all differences are reported.

use crate::perturbation::{Between, CatalogueEntry, FrameKey};
use crate::severity::Severity;
use crate::testing::{self, EntryOnGpu};
use crate::twin::TwinRun;
use crate::CATALOGUE;

/// Not a multiple of 8 (runs of 8 pixels per invocation, 8×8 workgroups) nor of 16 (JPEG's
/// MCUs, hysteresis tiles), so partial runs, workgroups and blocks are exercised.
const WIDTH: u32 = 77;
const HEIGHT: u32 = 53;

const SEVERITIES: [u8; 3] = [1, 3, 5];

/// Real severities, run by entries that interpolate their parameters: one below severity 1
/// (interpolated from the clean parameters) and one between two rows.
const REAL_SEVERITIES: [u16; 2] = [45, 250];

/// (seed, frame) pairs: another seed and a later frame give random entries other draws (and
/// make frost regenerate its per-seed texture between frames).
const SEEDS_FRAMES: [(u64, u32); 2] = [(5, 0), (6, 3)];

/// One GPU run of an entry and its twin on the same frame and key; whether it changed the frame.
fn check(
    entry: &CatalogueEntry,
    gpu: &mut EntryOnGpu,
    twin: &mut TwinRun,
    clean: &testing::Frame,
    key: &FrameKey,
) -> Result<bool, String> {
    let label = match key.explicit {
        Some(values) => format!("{}:{values:?}", entry.name),
        None => format!("{}:{}", entry.name, key.severity),
    };
    let label = format!("{label}-seed{}-frame{}", key.seed, key.frame);
    let actual = gpu
        .apply(key, &clean.color, Some(&clean.depth))
        .map_err(|e| format!("{label}: {e}"))?;
    let mut expected = clean.clone();
    twin.apply(&mut expected.color, &mut expected.depth, key);
    let tolerance = &entry.twin_tolerance;
    let color = testing::compare_color(&actual.color, &expected.color, tolerance, &label);
    let depth = testing::compare_depth(&actual.depth, &expected.depth, tolerance.metres, &label);
    let messages: Vec<String> = [color, depth].into_iter().filter_map(Result::err).collect();
    if !messages.is_empty() {
        return Err(messages.join("\n"));
    }
    Ok(actual != *clean)
}

/// The keys an entry runs with: each severity at each (seed, frame), its real severities
/// where it interpolates, then its explicit form.
fn keys<'a>(entry: &CatalogueEntry, explicit: Option<&'a [f64]>) -> Vec<FrameKey<'a>> {
    let whole = SEVERITIES.map(|s| Severity::whole(s).unwrap());
    let real = REAL_SEVERITIES.map(|h| Severity::from_hundredths(h).unwrap());
    let severities = match entry.between {
        Between::Interpolated(_) => [whole.as_slice(), &real].concat(),
        Between::WholeOnly(_) => whole.to_vec(),
    };
    let mut keys: Vec<FrameKey> = severities
        .into_iter()
        .flat_map(|severity| {
            SEEDS_FRAMES.map(|(seed, frame)| FrameKey {
                seed,
                frame,
                severity,
                explicit: None,
                camera: Some(testing::camera(WIDTH, HEIGHT)),
            })
        })
        .collect();
    if let Some(values) = explicit {
        let (seed, frame) = SEEDS_FRAMES[0];
        // An explicit form runs at severity 5 (see `FrameKey::severity`).
        keys.push(FrameKey {
            seed,
            frame,
            severity: Severity::MAX,
            explicit: Some(values),
            camera: Some(testing::camera(WIDTH, HEIGHT)),
        });
    }
    keys
}

#[test]
fn every_entry_matches_its_twin() {
    assert!(!CATALOGUE.is_empty(), "the catalogue is empty");
    let clean = testing::Frame {
        color: testing::test_image(WIDTH, HEIGHT),
        depth: testing::test_depth(WIDTH, HEIGHT),
    };
    let mut failures = Vec::new();
    let mut cases = 0;
    for entry in CATALOGUE {
        let explicit = match &entry.explicit {
            Some(form) => match (form.parse)(form.example) {
                Ok(values) => Some(values),
                Err(e) => {
                    failures.push(format!("{}: example {:?}: {e}", entry.name, form.example));
                    continue;
                }
            },
            None => None,
        };
        let mut gpu = match EntryOnGpu::new(entry, WIDTH, HEIGHT) {
            Ok(gpu) => gpu,
            Err(e) => {
                failures.push(format!("{}: {e}", entry.name));
                continue;
            }
        };
        // Built once like the GPU pass, so a stateful twin sees the same frames in the same order.
        let mut twin = entry.twin.start();
        let (mut changed, failed_before) = (false, failures.len());
        for key in keys(entry, explicit.as_deref()) {
            cases += 1;
            match check(entry, &mut gpu, &mut twin, &clean, &key) {
                Ok(changed_frame) => changed |= changed_frame,
                Err(e) => failures.push(e),
            }
        }
        // A pass that does nothing would match a twin that does nothing.
        if !changed && failures.len() == failed_before {
            failures.push(format!("{}: left the test frame as it was", entry.name));
        }
    }
    assert!(
        failures.is_empty(),
        "{} failures in {cases} cases of {} entries:\n{}",
        failures.len(),
        CATALOGUE.len(),
        failures.join("\n")
    );
}
