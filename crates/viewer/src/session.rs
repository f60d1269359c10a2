//! The viewer's state and logic without a window: what sequence, which frame, which spec, what is
//! on the GPU to show, the trajectory panel's data, the free camera, export. The egui code only
//! draws a [`Session`] and turns input into calls on it; tests drive it directly.

use std::path::{Path, PathBuf};

use rslam_core::dataset::{
    encode_depth_png, encode_png, read_dataset, write_atomically, DatasetFormat, DatasetOverrides,
    DepthPng,
};
use rslam_core::Pose;
use rslam_gpu::GpuContext;
use rslam_perturb::PerturbSpec;
use rslam_pipeline::{DepthRange, PixelReadout, RgbdFrame, SceneJob, ShownFrame};

use crate::free_camera::{CameraStep, FreeCamera};
use crate::playback::Playback;
use crate::sequence::Sequence;
use crate::spec_editor::SpecEditor;
use crate::trajectory_view::{EstimateOverlay, TrajectoryView};
use crate::ViewerError;

/// Where the frames come from.
#[derive(Clone, Debug)]
pub enum ViewSource {
    /// A built-in scene or mesh along a path; the job's spec and seed are replaced by the
    /// options'.
    Scene(Box<SceneJob>),
    /// A dataset folder (Replica or TUM layout).
    Dataset(PathBuf),
}

/// What `rslam view` opens.
#[derive(Clone, Debug)]
pub struct ViewOptions {
    pub source: ViewSource,
    pub spec: PerturbSpec,
    pub seed: u64,
    /// An estimated trajectory to align to the ground truth and colour by error.
    pub estimate: Option<PathBuf>,
}

/// Depth PNGs written by export use the Replica scale (1/6553.5 m per unit).
const EXPORT_FORMAT: DatasetFormat = DatasetFormat::Replica;

pub struct Session {
    pub ctx: GpuContext,
    pub sequence: Option<Sequence>,
    shown: Option<ShownFrame>,
    pub editor: SpecEditor,
    /// The spec the shown frame has, canonical (what `--perturb` takes).
    applied: PerturbSpec,
    pub seed: u64,
    index: usize,
    pub playback: Playback,
    pub depth_range: DepthRange,
    pub trajectory: TrajectoryView,
    estimate_path: Option<PathBuf>,
    pub camera: FreeCamera,
    /// The last error, one line, shown in the window until the next success.
    pub error: Option<String>,
    /// The last thing done (export, save), one line.
    pub notice: Option<String>,
    needs_show: bool,
    /// Frames put on the GPU so far (for the fps measurement).
    pub shows: u64,
}

impl Session {
    /// Opens `options` on `ctx`. Never fails: what cannot be opened becomes [`Session::error`]
    /// and the window shows it.
    pub fn open(ctx: GpuContext, options: &ViewOptions) -> Self {
        let mut session = Self {
            ctx,
            sequence: None,
            shown: None,
            editor: SpecEditor::from_spec(&options.spec),
            applied: options.spec.clone(),
            seed: options.seed,
            index: 0,
            playback: Playback::default(),
            depth_range: DepthRange::default(),
            trajectory: TrajectoryView::default(),
            estimate_path: options.estimate.clone(),
            camera: FreeCamera::default(),
            error: None,
            notice: None,
            needs_show: true,
            shows: 0,
        };
        match session.open_sequence(options) {
            Ok(sequence) => {
                session.sequence = Some(sequence);
                session.refresh_trajectory();
            }
            Err(e) => session.error = Some(e.to_string()),
        }
        session
    }

    fn open_sequence(&self, options: &ViewOptions) -> Result<Sequence, ViewerError> {
        Ok(match &options.source {
            ViewSource::Scene(job) => {
                let job = SceneJob {
                    spec: options.spec.clone(),
                    seed: options.seed,
                    agent: None,
                    capture: Default::default(),
                    ..(**job).clone()
                };
                Sequence::scene(&self.ctx, &job)?
            }
            ViewSource::Dataset(root) => {
                let dataset = read_dataset(root, &DatasetOverrides::default())?;
                Sequence::dataset(&self.ctx, &dataset, &options.spec, options.seed)?
            }
        })
    }

    /// The current output frame.
    pub fn index(&self) -> usize {
        self.index
    }

    /// Output frames (0 when nothing is open).
    pub fn len(&self) -> usize {
        self.sequence.as_ref().map_or(0, Sequence::len)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    pub fn applied_spec(&self) -> &PerturbSpec {
        &self.applied
    }

    /// The spec string of the shown frame, as `rslam render --perturb` takes it.
    pub fn spec_string(&self) -> String {
        self.applied.to_string()
    }

    pub fn set_index(&mut self, index: usize) {
        let index = index.min(self.len().saturating_sub(1));
        if index != self.index {
            self.index = index;
            self.needs_show = true;
        }
    }

    pub fn step(&mut self, forward: bool) {
        match forward {
            true => self.set_index(self.index + 1),
            false => self.set_index(self.index.saturating_sub(1)),
        }
    }

    /// Advances play by `dt` seconds at the sequence rate.
    pub fn tick(&mut self, dt: f64) {
        let Some(sequence) = &self.sequence else {
            return;
        };
        let (rate, len) = (sequence.rate_hz(), sequence.len());
        let next = self.playback.advance(dt, rate, self.index, len);
        self.set_index(next);
    }

    /// Applies what the perturbation panel holds; a bad spec leaves the shown one in place and
    /// becomes the error line.
    pub fn apply_editor(&mut self) {
        match self.editor.spec() {
            Ok(spec) => self.apply_spec(spec, false),
            Err(e) => self.error = Some(e.to_string()),
        }
    }

    /// Applies a typed spec string (the panel's text field); the panel takes its items.
    pub fn apply_spec_text(&mut self, text: &str) {
        let parsed = match text.trim() {
            "" => Ok(PerturbSpec::default()),
            t => PerturbSpec::parse(t),
        };
        match parsed {
            Ok(spec) => {
                self.editor = SpecEditor::from_spec(&spec);
                self.apply_spec(spec, false);
            }
            Err(e) => self.error = Some(format!("spec: {e}")),
        }
    }

    /// Takes `spec` unless it is the one shown already (`force`: take it anyway, e.g. for a new
    /// seed).
    fn apply_spec(&mut self, spec: PerturbSpec, force: bool) {
        if spec == self.applied && self.error.is_none() && !force {
            return;
        }
        let Some(sequence) = &mut self.sequence else {
            return;
        };
        match sequence.set_spec(&self.ctx, &spec, self.seed) {
            Ok(()) => {
                self.applied = spec;
                self.error = None;
                self.needs_show = true;
                let last = self.len().saturating_sub(1);
                self.index = self.index.min(last);
                self.refresh_trajectory();
            }
            Err(e) => self.error = Some(e.to_string()),
        }
    }

    pub fn set_seed(&mut self, seed: u64) {
        if seed != self.seed {
            self.seed = seed;
            self.apply_spec(self.applied.clone(), true);
        }
    }

    pub fn set_depth_range(&mut self, range: DepthRange) {
        if range != self.depth_range && range.far > range.near {
            self.depth_range = range;
            self.needs_show = true;
        }
    }

    fn refresh_trajectory(&mut self) {
        let Some(sequence) = &self.sequence else {
            return;
        };
        let ground_truth = sequence.ground_truth();
        if ground_truth == self.trajectory.ground_truth && self.trajectory.estimate.is_some() {
            return;
        }
        self.trajectory.estimate = None;
        if let Some(path) = &self.estimate_path {
            match EstimateOverlay::new(path, &ground_truth) {
                Ok(overlay) => self.trajectory.estimate = Some(overlay),
                Err(e) => self.error = Some(e.to_string()),
            }
        }
        self.trajectory.ground_truth = ground_truth;
    }

    /// The ground-truth pose of the current frame: the trajectory panel's marker.
    pub fn marker(&self) -> Option<Pose> {
        let sequence = self.sequence.as_ref()?;
        let time = sequence.plan().frames.get(self.index)?.rgb_time;
        self.trajectory.pose_at(time, 0.5 / sequence.rate_hz())
    }

    /// Puts the current frame on the GPU if anything changed since it was last shown; says
    /// whether it did.
    pub fn refresh(&mut self) -> bool {
        if !self.needs_show {
            return false;
        }
        self.needs_show = false;
        if let Err(e) = self.show_now() {
            self.error = Some(e.to_string());
        }
        true
    }

    fn show_now(&mut self) -> Result<(), ViewerError> {
        let Some(sequence) = &mut self.sequence else {
            return Ok(());
        };
        let (width, height) = sequence.size();
        if self.shown.as_ref().map(ShownFrame::size) != Some((width, height)) {
            self.shown = Some(ShownFrame::new(&self.ctx, width, height)?);
        }
        let Some(shown) = &mut self.shown else {
            return Ok(());
        };
        let pose = self.camera.active.then_some(&self.camera.world_from_camera);
        sequence.show(&self.ctx, self.index, pose, shown, self.depth_range)?;
        self.shows += 1;
        Ok(())
    }

    /// The frame on the GPU, once something has been shown.
    pub fn shown(&self) -> Option<&ShownFrame> {
        self.shown.as_ref().filter(|s| s.sources().is_some())
    }

    /// Colour and depth under pixel (`x`, `y`) of the shown frame.
    pub fn pixel(&mut self, x: u32, y: u32) -> Option<PixelReadout> {
        let shown = self.shown.as_ref()?;
        match shown.read_pixel(&self.ctx, x, y) {
            Ok(readout) => readout,
            Err(e) => {
                self.error = Some(e.to_string());
                None
            }
        }
    }

    /// Switches the free camera on (starting from the current frame's pose) or off.
    pub fn set_free_camera(&mut self, active: bool) {
        if active == self.camera.active {
            return;
        }
        if active {
            if !self.sequence.as_ref().is_some_and(Sequence::is_scene) {
                self.error = Some("free camera: only a scene can be seen from a new pose".into());
                return;
            }
            if let Some(pose) = self.marker() {
                self.camera.snap_to(pose);
            }
        }
        self.camera.active = active;
        self.needs_show = true;
    }

    pub fn fly(&mut self, step: CameraStep) {
        if self.camera.active && !step.is_still() {
            self.camera.fly(step);
            self.needs_show = true;
        }
    }

    /// The free camera back onto the path at the current frame.
    pub fn snap_back(&mut self) {
        if let Some(pose) = self.marker() {
            self.camera.snap_to(pose);
            self.needs_show = true;
        }
    }

    pub fn save_camera_path(&mut self, path: &Path) {
        let rate = self.sequence.as_ref().map_or(20.0, Sequence::rate_hz);
        match self.camera.save(path, rate) {
            Ok(()) => {
                self.notice = Some(format!(
                    "saved {} poses to {}",
                    self.camera.recorded.len(),
                    path.display()
                ));
            }
            Err(e) => self.error = Some(e.to_string()),
        }
    }

    /// Writes the current output frame, perturbed, as `frameNNNNNN.png` and `depthNNNNNN.png`
    /// (16-bit, Replica scale) into `dir`.
    pub fn export_frame(&mut self, dir: &Path) -> Result<Vec<PathBuf>, ViewerError> {
        let index = self.index;
        self.export_range(dir, index..index + 1)
    }

    /// Writes `count` output frames from the current one into the folder `dir`, with the spec
    /// that made them in `spec.txt`.
    pub fn export_clip(&mut self, dir: &Path, count: usize) -> Result<Vec<PathBuf>, ViewerError> {
        let end = (self.index + count.max(1)).min(self.len());
        let mut written = self.export_range(dir, self.index..end)?;
        let spec = dir.join("spec.txt");
        write_atomically(&spec, format!("{}\n", self.spec_string()).as_bytes())?;
        written.push(spec);
        Ok(written)
    }

    fn export_range(
        &mut self,
        dir: &Path,
        range: std::ops::Range<usize>,
    ) -> Result<Vec<PathBuf>, ViewerError> {
        let Some(sequence) = &mut self.sequence else {
            return Err(ViewerError::File {
                path: dir.to_path_buf(),
                message: "nothing is open to export".into(),
            });
        };
        std::fs::create_dir_all(dir).map_err(|e| rslam_core::CoreError::io(dir, e))?;
        let mut written = Vec::new();
        let mut write = |frame: RgbdFrame| -> Result<(), rslam_pipeline::PipelineError> {
            written.extend(write_frame(dir, &frame)?);
            Ok(())
        };
        sequence.frames(&self.ctx, range, &mut write)?;
        self.notice = Some(format!(
            "wrote {} files to {}",
            written.len(),
            dir.display()
        ));
        Ok(written)
    }
}

fn write_frame(dir: &Path, frame: &RgbdFrame) -> Result<Vec<PathBuf>, rslam_core::CoreError> {
    let rgb = dir.join(format!("frame{:06}.png", frame.index));
    write_atomically(&rgb, &encode_png(&frame.color)?)?;
    let mut written = vec![rgb];
    if let Some(depth) = &frame.depth {
        let path = dir.join(format!("depth{:06}.png", frame.index));
        let bytes = encode_depth_png(depth, EXPORT_FORMAT.depth_scale(), DepthPng::Fast)?;
        write_atomically(&path, &bytes)?;
        written.push(path);
    }
    Ok(written)
}
