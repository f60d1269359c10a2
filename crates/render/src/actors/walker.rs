//! A walking person: an articulated low-poly body posed at any instant of a walking gait.
//!
//! The body is a set of closed parts, each rigid on one bone of a kinematic chain (pelvis →
//! chest → head and arms; pelvis → thighs → shins → feet). The feet drive the gait: each is on
//! the floor for [`STANCE`] of a cycle, rolling from the heel over the sole to the toes, and
//! swings forward for the rest. The pelvis rides as high as both legs reach their feet, and the
//! legs follow by two-bone inverse kinematics, so a planted sole neither slides nor sinks.

use std::f32::consts::{FRAC_PI_2, PI, TAU};
use std::iter::{once, repeat_n};

use glam::{Affine3A, FloatExt, Mat3, Quat, Vec2, Vec3};

use crate::scene::builtin::rng::Rng;

/// The longest step a body is posed with, metres.
pub const MAX_STRIDE: f32 = 0.9;

/// A carried box's depth and height, metres; its width is what the hands hold apart less
/// [`CARTON_GRIP`] (the palms' thickness).
const CARTON_DEPTH: (f32, f32) = (0.3, 0.4);
const CARTON_HEIGHT: (f32, f32) = (0.22, 0.32);
const CARTON_GRIP: f32 = 0.04;
/// How far a carried box reaches below the palms, metres.
const CARTON_BELOW_PALMS: f32 = 0.08;
/// Shoulder flexion while carrying, radians.
const CARRY_SHOULDER: f32 = 0.3;

/// Fraction of a gait cycle each foot is on the floor.
const STANCE: f32 = 0.6;
/// A foot's own phase when its sole comes down flat after the heel strike.
const FOOT_FLAT: f32 = 0.1;
/// A foot's own phase when its heel lifts.
const HEEL_OFF: f32 = 0.35;
/// A foot's own phase when its knee has straightened again after taking the body's weight.
const LOADING_END: f32 = 0.3;
/// Fraction of the swing over which the foot turns from its toe-off to its heel-strike pitch.
const SWING_TURN: f32 = 0.8;
/// Fraction of the swing over which the ankle sinks from its toe-off to its heel-strike height.
const SWING_SINK: f32 = 0.6;

/// Step length of an ordinary walk, metres: the amplitudes below are at it and scale with the
/// step.
const USUAL_STRIDE: f32 = 0.7;
const HEEL_STRIKE_PITCH: f32 = 15f32.to_radians();
const TOE_OFF_PITCH: f32 = 45f32.to_radians();
/// Height the swinging ankle rises above its path from toe-off to heel strike, metres.
const SWING_LIFT: f32 = 0.09;
/// Extra knee flexion as the leg takes the body's weight.
const LOADING_KNEE: f32 = 15f32.to_radians();
/// Knee flexion of a straight leg: a locked knee would leave the inverse kinematics no slack.
const STRAIGHT_KNEE: f32 = 3f32.to_radians();
const PELVIS_YAW: f32 = 5f32.to_radians();
const PELVIS_ROLL: f32 = 3f32.to_radians();
/// Sideways shift of the pelvis over the stance foot, metres.
const PELVIS_SWAY: f32 = 0.02;
const CHEST_YAW: f32 = 4f32.to_radians();
const LEAN: f32 = 3f32.to_radians();
const ARM_SWING: f32 = 18f32.to_radians();
const ELBOW_REST: f32 = 8f32.to_radians();
const ELBOW_WALK: f32 = 10f32.to_radians();
/// Backward tilt of the head's long axis (chin forward and down, crown back and up).
const HEAD_TILT: f32 = 30f32.to_radians();

/// Forward and sideways radii of the hips and of the forearm below the elbow at girth 1, metres
/// (the arms hang out far enough for one to clear the other).
const HIPS: [f32; 2] = [0.105, 0.165];
const FOREARM: [f32; 2] = [0.037, 0.036];

/// Sides of a limb's cross-section, and of the torso's and head's.
const LIMB_SIDES: usize = 8;
const TORSO_SIDES: usize = 12;

/// What a vertex of a walker is made of; the caller maps each to a texture and a tint.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BodyMaterial {
    Top,
    Trousers,
    Skin,
    Hair,
    Shoes,
    /// A box in the hands.
    Carton,
}

/// Triangles of posed bodies: every part of a body is a closed surface with smooth normals
/// (flat ones on the hands and feet).
#[derive(Clone, Debug, Default)]
pub struct PosedMesh {
    pub positions: Vec<Vec3>,
    /// Unit outward normals.
    pub normals: Vec<Vec3>,
    /// Texture coordinates in metres (cylindrical around each limb / torso: u = arc length
    /// around, v = length along), so a tiling cloth texture of ~0.5 m repeat looks right.
    pub uvs: Vec<Vec2>,
    pub materials: Vec<BodyMaterial>,
    /// Three per triangle, counter-clockwise seen from outside.
    pub indices: Vec<u32>,
}

/// One walker's build, drawn from a seed: its measurements and its parts at rest.
#[derive(Clone, Debug, PartialEq)]
pub struct WalkerBody {
    build: Build,
    parts: Vec<Part>,
    /// The box it carries in both hands, if any: its depth, width and height, metres.
    carton: Option<Vec3>,
}

impl WalkerBody {
    /// A body of stature 1.55–1.90 m with proportions varied a little (shoulder width, girth,
    /// leg length, head size), hair and clothes (sleeves, shorts), from `rng`.
    pub fn new(rng: &mut Rng) -> Self {
        let stature = rng.range(1.55, 1.90);
        let look = Look::draw(rng, stature);
        let head = head_parts(&look);
        let crown = head
            .iter()
            .flat_map(|part| &part.surface.positions)
            .map(|p| p.z)
            .fold(f32::MIN, f32::max);
        let build = Build::new(stature, crown, &look);
        let mut parts = body_parts(&build, &look);
        parts.extend(head);
        Self {
            build,
            parts,
            carton: None,
        }
    }

    /// The body carrying a box in both hands before it (forearms level, palms on its sides), of
    /// a size drawn from `rng` as wide as its hands hold apart.
    pub fn carrying(mut self, rng: &mut Rng) -> Self {
        let depth = rng.range(CARTON_DEPTH.0, CARTON_DEPTH.1);
        let height = rng.range(CARTON_HEIGHT.0, CARTON_HEIGHT.1);
        self.carton = Some(Vec3::new(depth, 0.0, height));
        let [left, right] = self.palms(&self.skeleton(0.0, 0.0));
        self.carton = Some(Vec3::new(depth, left.distance(right) - CARTON_GRIP, height));
        self
    }

    /// Whether it carries a box.
    pub fn carries(&self) -> bool {
        self.carton.is_some()
    }

    /// Stature, metres (top of the head over the soles).
    pub fn height(&self) -> f32 {
        self.build.stature
    }

    /// Appends the body posed at gait `phase` (turns: one cycle = two steps, left then right,
    /// phase 0 = left heel strike) with step length `stride` (metres, within 0..=[`MAX_STRIDE`];
    /// 0 = standing still, arms hanging), in the body frame: x forward, y left, z up, soles at
    /// z = 0 when planted, body centred over the origin. A cycle covers `2 * stride` metres.
    pub fn pose(&self, phase: f32, stride: f32, out: &mut PosedMesh) {
        let skeleton = self.skeleton(phase, stride);
        for part in &self.parts {
            let bone = skeleton.bone(part.bone);
            let surface = &part.surface;
            let base = out.positions.len() as u32;
            out.positions
                .extend(surface.positions.iter().map(|&p| bone.transform_point3(p)));
            out.normals
                .extend(surface.normals.iter().map(|&n| bone.transform_vector3(n)));
            out.uvs.extend_from_slice(&surface.uvs);
            out.materials
                .extend(repeat_n(part.material, surface.positions.len()));
            out.indices
                .extend(surface.indices.iter().map(|&i| base + i));
        }
        if let Some(size) = self.carton {
            let [left, right] = self.palms(&skeleton);
            // Held at the middle of the palms, its bottom a little below them.
            let centre = (left + right) / 2.0 + Vec3::Z * (size.z / 2.0 - CARTON_BELOW_PALMS);
            let (_, turn, _) = skeleton.chest.to_scale_rotation_translation();
            let yaw = Quat::from_rotation_z(turn.to_euler(glam::EulerRot::ZYX).0);
            let corners = std::array::from_fn(|i| {
                let bit = |b: usize| if i & b != 0 { 0.5 } else { -0.5 };
                centre + yaw * (Vec3::new(bit(1), bit(2), bit(4)) * size)
            });
            let surface = hexahedron(corners);
            let base = out.positions.len() as u32;
            out.positions.extend_from_slice(&surface.positions);
            out.normals.extend_from_slice(&surface.normals);
            out.uvs.extend_from_slice(&surface.uvs);
            (out.materials).extend(repeat_n(BodyMaterial::Carton, surface.positions.len()));
            (out.indices).extend(surface.indices.iter().map(|&i| base + i));
        }
    }

    /// The middles of the palms of a body posed as `skeleton`, left then right.
    fn palms(&self, skeleton: &Skeleton) -> [Vec3; 2] {
        let b = &self.build;
        let reach = b.forearm + 0.5 * b.hand;
        Side::BOTH.map(|side| skeleton.arms[side as usize][1].transform_point3(Vec3::NEG_Z * reach))
    }

    /// The farthest any vertex gets from the body's axis over the gait at steps up to
    /// [`MAX_STRIDE`], sampled.
    /// Every bone's frame at `phase` and `stride`.
    fn skeleton(&self, phase: f32, stride: f32) -> Skeleton {
        let b = &self.build;
        let gait = Gait::new(phase, stride);
        let feet = Side::BOTH.map(|side| self.foot(side, &gait));
        let pelvis_turn = gait.pelvis_turn();
        let hips = Side::BOTH.map(|side| pelvis_turn * b.hip(side));
        let height = self.pelvis_height(&gait, &feet, &hips);
        let pelvis =
            Affine3A::from_rotation_translation(pelvis_turn, Vec3::new(0.0, gait.sway(), height));
        let chest_turn = gait.chest_turn();
        let chest = Affine3A::from_rotation_translation(
            chest_turn,
            pelvis.transform_point3(Vec3::Z * b.waist),
        );
        Skeleton {
            pelvis,
            chest,
            head: Affine3A::from_translation(chest.transform_point3(Vec3::Z * b.head)),
            arms: Side::BOTH.map(|side| self.arm(&chest, chest_turn, side, &gait)),
            legs: Side::BOTH
                .map(|side| self.leg(pelvis.transform_point3(b.hip(side)), feet[side as usize])),
        }
    }

    /// The highest the pelvis can ride with each leg reaching its foot with the knee bent at
    /// least as far as the gait asks (the swing leg too, so that the height runs on smoothly
    /// when its foot comes down).
    fn pelvis_height(&self, gait: &Gait, feet: &[FootPose; 2], hips: &[Vec3; 2]) -> f32 {
        let b = &self.build;
        Side::BOTH
            .into_iter()
            .map(|side| {
                let (foot, hip) = (feet[side as usize], hips[side as usize]);
                let reach = b.leg_reach(STRAIGHT_KNEE + gait.loading_knee(side));
                let across = foot.ankle.truncate() - hip.truncate() - Vec2::Y * gait.sway();
                let rise = (reach * reach - across.length_squared()).max(0.0).sqrt();
                foot.ankle.z + rise - hip.z
            })
            .fold(f32::MAX, f32::min)
    }

    /// Where `side`'s foot is: planted and rolling heel to toe, or swinging forward.
    fn foot(&self, side: Side, gait: &Gait) -> FootPose {
        let own = gait.own_phase(side);
        // People walk on a narrower track than their hips.
        let y = side.sign() * self.build.hip_half * (1.0 - 0.25 * gait.amplitude.min(1.0));
        if own < STANCE {
            self.stance_foot(own, y, gait)
        } else {
            self.swing_foot((own - STANCE) / (1.0 - STANCE), y, gait)
        }
    }

    /// The planted foot at its own phase `own`: it keeps its place on the floor, which runs
    /// back under the body at the walking speed.
    fn stance_foot(&self, own: f32, y: f32, gait: &Gait) -> FootPose {
        let b = &self.build;
        // The sole spans from the heel at the strike to the toes at toe-off, centred on the hips.
        let strike = STANCE * gait.stride + 0.5 * (b.heel - b.toe) * gait.amplitude.min(1.0);
        let x = strike - 2.0 * gait.stride * own;
        let a = gait.amplitude;
        let pitch = if own < FOOT_FLAT {
            -HEEL_STRIKE_PITCH * a * (1.0 - smooth(own / FOOT_FLAT))
        } else if own < HEEL_OFF {
            0.0
        } else {
            TOE_OFF_PITCH * a * ((own - HEEL_OFF) / (STANCE - HEEL_OFF)).powi(2)
        };
        self.rolled(Vec3::new(x, y, b.ankle), pitch)
    }

    /// The swinging foot `t` of the way from toe-off to the next heel strike.
    fn swing_foot(&self, t: f32, y: f32, gait: &Gait) -> FootPose {
        let lift_off = self.stance_foot(STANCE, y, gait);
        let strike = self.stance_foot(0.0, y, gait);
        // The body moves on during the swing; the foot leaves and meets the floor at rest
        // relative to it, that is moving back at the walking speed in the body frame.
        let travel = 2.0 * gait.stride * (1.0 - STANCE);
        let ahead = strike.ankle.x - lift_off.ankle.x + travel;
        let x = lift_off.ankle.x + ahead * smooth(t) - travel * t;
        let z = lift_off
            .ankle
            .z
            .lerp(strike.ankle.z, smooth((t / SWING_SINK).min(1.0)))
            + SWING_LIFT * gait.amplitude * early_bump(t);
        let pitch = lift_off
            .pitch
            .lerp(strike.pitch, smooth((t / SWING_TURN).min(1.0)));
        // The toes only rise from the floor as the heel comes down and the ankle lifts, and the
        // heel meets it from above: the shoe stays clear all along.
        FootPose {
            ankle: Vec3::new(x, y, z),
            pitch,
        }
    }

    /// The foot lying flat with its ankle at `flat`, rolled by `pitch` (heel up positive) about
    /// the edge it keeps on the floor: the back of the heel with the toes up, the tips of the
    /// toes with the heel up.
    fn rolled(&self, flat: Vec3, pitch: f32) -> FootPose {
        let b = &self.build;
        let edge = if pitch < 0.0 { -b.heel } else { b.toe };
        let pivot = flat + Vec3::new(edge, 0.0, -b.ankle);
        FootPose {
            ankle: pivot + Quat::from_rotation_y(pitch) * (flat - pivot),
            pitch,
        }
    }

    /// Thigh, shin and foot of the leg from `hip` to `foot`, the knee bending forward.
    fn leg(&self, hip: Vec3, foot: FootPose) -> [Affine3A; 3] {
        let (thigh, shin) = (self.build.thigh, self.build.shin);
        let to_ankle = foot.ankle - hip;
        let reach = to_ankle
            .length()
            .clamp((thigh - shin).abs() + 1e-4, thigh + shin - 1e-4);
        let down = to_ankle.normalize();
        let along = (thigh * thigh - shin * shin + reach * reach) / (2.0 * reach);
        let out = (thigh * thigh - along * along).max(0.0).sqrt();
        let knee = hip + down * along + square_to(Vec3::X, down) * out;
        [
            limb_frame(hip, knee - hip),
            limb_frame(knee, foot.ankle - knee),
            Affine3A::from_rotation_translation(Quat::from_rotation_y(foot.pitch), foot.ankle),
        ]
    }

    /// Upper arm and forearm of `side`, hanging from the shoulder and swinging against the leg.
    /// Carrying, the arm holds still: the upper arm a little forward, the forearm level.
    fn arm(&self, chest: &Affine3A, chest_turn: Quat, side: Side, gait: &Gait) -> [Affine3A; 2] {
        let b = &self.build;
        let (swing, elbow) = match self.carton {
            Some(_) => (CARRY_SHOULDER, FRAC_PI_2 - CARRY_SHOULDER),
            None => (gait.arm_swing(side), gait.elbow(gait.arm_swing(side))),
        };
        let shoulder =
            chest.transform_point3(Vec3::new(0.0, side.sign() * b.shoulder_half, b.shoulder));
        let turn = chest_turn
            * Quat::from_rotation_x(side.sign() * b.abduction)
            * Quat::from_rotation_y(-swing);
        let upper = Affine3A::from_rotation_translation(turn, shoulder);
        let elbow = Affine3A::from_rotation_translation(
            Quat::from_rotation_y(-elbow),
            Vec3::NEG_Z * b.upper_arm,
        );
        [upper, upper * elbow]
    }
}

/// The two sides of the body; as an index, left is 0.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Side {
    Left,
    Right,
}

impl Side {
    const BOTH: [Side; 2] = [Side::Left, Side::Right];

    /// +1 on the left (+y), −1 on the right.
    fn sign(self) -> f32 {
        match self {
            Side::Left => 1.0,
            Side::Right => -1.0,
        }
    }
}

/// The bone a part rides on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Bone {
    Pelvis,
    Chest,
    Head,
    UpperArm(Side),
    Forearm(Side),
    Thigh(Side),
    Shin(Side),
    Foot(Side),
}

/// Every bone's frame at one instant: its rest frame (joint at the origin, x forward, y left,
/// z up, limbs hanging along −z) placed in the body frame.
struct Skeleton {
    pelvis: Affine3A,
    chest: Affine3A,
    head: Affine3A,
    /// Upper arm and forearm of each side.
    arms: [[Affine3A; 2]; 2],
    /// Thigh, shin and foot of each side.
    legs: [[Affine3A; 3]; 2],
}

impl Skeleton {
    fn bone(&self, bone: Bone) -> Affine3A {
        match bone {
            Bone::Pelvis => self.pelvis,
            Bone::Chest => self.chest,
            Bone::Head => self.head,
            Bone::UpperArm(side) => self.arms[side as usize][0],
            Bone::Forearm(side) => self.arms[side as usize][1],
            Bone::Thigh(side) => self.legs[side as usize][0],
            Bone::Shin(side) => self.legs[side as usize][1],
            Bone::Foot(side) => self.legs[side as usize][2],
        }
    }
}

/// A foot's place: its ankle joint, and its pitch about y (heel up positive).
#[derive(Clone, Copy, Debug)]
struct FootPose {
    ankle: Vec3,
    pitch: f32,
}

/// One instant of the gait.
struct Gait {
    /// Turns in [0, 1), 0 at the left heel strike.
    phase: f32,
    /// Step length, metres.
    stride: f32,
    /// Step length over [`USUAL_STRIDE`]: every swing and turn of the body scales with it.
    amplitude: f32,
}

impl Gait {
    fn new(phase: f32, stride: f32) -> Self {
        let stride = stride.clamp(0.0, MAX_STRIDE);
        Self {
            phase: phase.rem_euclid(1.0),
            stride,
            amplitude: stride / USUAL_STRIDE,
        }
    }

    /// `side`'s own phase, 0 at its heel strike: the right leg runs half a cycle behind.
    fn own_phase(&self, side: Side) -> f32 {
        match side {
            Side::Left => self.phase,
            Side::Right => (self.phase + 0.5).fract(),
        }
    }

    /// +1 at the left heel strike (left leg ahead), −1 at the right.
    fn lead(&self) -> f32 {
        (TAU * self.phase).cos()
    }

    /// +1 in the middle of the left foot's stance, −1 in the middle of the right's.
    fn weight(&self) -> f32 {
        (TAU * self.phase).sin()
    }

    /// The pelvis turns its leading hip forward and drops on the swinging side.
    fn pelvis_turn(&self) -> Quat {
        let a = self.amplitude;
        Quat::from_rotation_z(-PELVIS_YAW * a * self.lead())
            * Quat::from_rotation_x(PELVIS_ROLL * a * self.weight())
    }

    fn sway(&self) -> f32 {
        PELVIS_SWAY * self.amplitude.min(1.0) * self.weight()
    }

    /// The chest turns against the pelvis and leans into the walk.
    fn chest_turn(&self) -> Quat {
        Quat::from_rotation_z(CHEST_YAW * self.amplitude * self.lead())
            * Quat::from_rotation_y(LEAN * self.amplitude.min(1.0))
    }

    /// Shoulder flexion of `side` (arm forward positive): ahead when the other leg is.
    fn arm_swing(&self, side: Side) -> f32 {
        -side.sign() * ARM_SWING * self.amplitude * self.lead()
    }

    /// Elbow flexion: a little bent, more as the arm swings forward.
    fn elbow(&self, swing: f32) -> f32 {
        ELBOW_REST + ELBOW_WALK * self.amplitude + 0.5 * swing
    }

    /// The knee flexion, beyond straight, with which `side`'s leg takes the body's weight after
    /// its heel strike.
    fn loading_knee(&self, side: Side) -> f32 {
        let own = self.own_phase(side);
        if own < LOADING_END {
            LOADING_KNEE * self.amplitude.min(1.0) * (PI * own / LOADING_END).sin().powi(2)
        } else {
            0.0
        }
    }
}

/// Cubic ease from 0 to 1 with zero slope at both ends.
fn smooth(t: f32) -> f32 {
    t * t * (3.0 - 2.0 * t)
}

/// A bump over [0, 1], zero at the ends and 1 at a third of the way.
fn early_bump(t: f32) -> f32 {
    6.75 * t * (1.0 - t) * (1.0 - t)
}

/// The unit vector along `v` square to the unit vector `axis`.
fn square_to(v: Vec3, axis: Vec3) -> Vec3 {
    (v - axis * v.dot(axis)).normalize()
}

/// The frame of a limb from `joint` along `down`: z back up the limb, x forward.
fn limb_frame(joint: Vec3, down: Vec3) -> Affine3A {
    let z = -down.normalize();
    let x = square_to(Vec3::X, z);
    Affine3A::from_mat3_translation(Mat3::from_cols(x, z.cross(x), z), joint)
}

/// What varies between bodies besides stature.
struct Look {
    /// Lengths over those of a 1.75 m adult.
    scale: f32,
    /// Factor on every girth.
    girth: f32,
    /// Factor on the breadth of the shoulders.
    shoulders: f32,
    /// Factor on the length of the legs (the torso takes the difference).
    legs: f32,
    /// Semi-axes of the head's ellipsoid, metres: front, side, along its tilted axis.
    head: Vec3,
    /// Where the hair ends along the head's tilted axis from its centre, and its thickness,
    /// metres.
    hairline: f32,
    hair: f32,
    short_sleeves: bool,
    shorts: bool,
}

impl Look {
    fn draw(rng: &mut Rng, stature: f32) -> Self {
        let scale = stature / 1.75;
        // Heads vary less with stature than limbs do.
        let head = Vec3::new(0.095, 0.078, 0.118) * scale.sqrt() * rng.range(0.95, 1.05);
        Self {
            scale,
            girth: rng.range(0.9, 1.15),
            shoulders: rng.range(0.93, 1.07),
            legs: rng.range(0.97, 1.03),
            hairline: head.z * rng.range(-0.3, 0.2),
            hair: rng.range(0.006, 0.018),
            head,
            short_sleeves: rng.chance(0.4),
            shorts: rng.chance(0.15),
        }
    }

    /// Radii forward and sideways of a 1.75 m adult's at this body's scale and girth.
    fn radii(&self, [rx, ry]: [f32; 2]) -> Vec2 {
        Vec2::new(rx, ry) * self.scale * self.girth
    }
}

/// A body's measurements, metres; every joint is the origin of its bone's rest frame.
#[derive(Clone, Debug, PartialEq)]
struct Build {
    stature: f32,
    /// Ankle joints over the soles.
    ankle: f32,
    shin: f32,
    thigh: f32,
    /// Hip joints from the mid-line.
    hip_half: f32,
    /// The chest's joint over the hip joints.
    waist: f32,
    /// Shoulder joints over the waist, and from the mid-line.
    shoulder: f32,
    shoulder_half: f32,
    /// The head's centre over the waist.
    head: f32,
    upper_arm: f32,
    forearm: f32,
    /// Hand from the wrist to the finger tips.
    hand: f32,
    /// How far out the arms hang, radians: enough to clear the hips.
    abduction: f32,
    /// The sole behind and ahead of the ankle.
    heel: f32,
    toe: f32,
    foot_width: f32,
}

impl Build {
    /// The measurements of a body `stature` tall whose crown is `crown` over its head's centre.
    fn new(stature: f32, crown: f32, look: &Look) -> Self {
        let l = look.scale;
        let (thigh, shin, ankle) = (0.43 * l * look.legs, 0.43 * l * look.legs, 0.068 * l);
        let hips = ankle + knee_chord(thigh, shin, STRAIGHT_KNEE);
        // Hip joints to the head's centre, shared out as in a 1.75 m adult.
        let upper = stature - hips - crown;
        let waist = 0.22 * upper;
        let shoulder = 0.69 * upper - waist;
        let shoulder_half = 0.18 * l * look.shoulders;
        let clear = look.radii(HIPS).y + look.radii(FOREARM).y + 0.01 - shoulder_half;
        let foot = 0.155 * l;
        Self {
            stature,
            ankle,
            shin,
            thigh,
            hip_half: 0.085 * l * look.girth.sqrt(),
            waist,
            shoulder,
            shoulder_half,
            head: upper - waist,
            upper_arm: 0.31 * l,
            forearm: 0.26 * l,
            hand: 0.18 * l,
            abduction: (clear / (waist + shoulder)).atan().max(4f32.to_radians()),
            heel: 0.22 * foot,
            toe: 0.78 * foot,
            foot_width: 0.1 * l,
        }
    }

    /// `side`'s hip joint in the pelvis frame.
    fn hip(&self, side: Side) -> Vec3 {
        Vec3::Y * side.sign() * self.hip_half
    }

    /// Hip to ankle with the knee bent by `knee`.
    fn leg_reach(&self, knee: f32) -> f32 {
        knee_chord(self.thigh, self.shin, knee)
    }

    /// The shoe's corners in the foot frame (index bits: toe end, left side, top).
    fn foot_corners(&self) -> [Vec3; 8] {
        std::array::from_fn(|i| {
            let toe_end = i & 1 != 0;
            let x = if toe_end { self.toe } else { -self.heel };
            let y = if i & 2 != 0 { 0.5 } else { -0.5 } * self.foot_width;
            let z = match (i & 4 != 0, toe_end) {
                (false, _) => -self.ankle,
                (true, false) => 0.3 * self.ankle,
                (true, true) => -0.4 * self.ankle,
            };
            Vec3::new(x, y, z)
        })
    }

    /// The hand's corners in the forearm frame (index bits: front, left side, top); the palm
    /// faces the thigh.
    fn hand_corners(&self, look: &Look) -> [Vec3; 8] {
        let (width, thickness) = (0.085 * look.scale, 0.03 * look.scale * look.girth);
        std::array::from_fn(|i| {
            Vec3::new(
                if i & 1 != 0 { 0.5 } else { -0.5 } * width,
                if i & 2 != 0 { 0.5 } else { -0.5 } * thickness,
                if i & 4 != 0 { 0.005 } else { -self.hand } - self.forearm,
            )
        })
    }
}

/// Distance from hip to ankle with the knee bent by `knee` radians.
fn knee_chord(thigh: f32, shin: f32, knee: f32) -> f32 {
    (thigh * thigh + shin * shin + 2.0 * thigh * shin * knee.cos()).sqrt()
}

/// A closed piece of the body, rigid on one bone, in that bone's rest frame.
#[derive(Clone, Debug, PartialEq)]
struct Part {
    bone: Bone,
    material: BodyMaterial,
    surface: Surface,
}

impl Part {
    fn new(bone: Bone, material: BodyMaterial, surface: Surface) -> Self {
        Self {
            bone,
            material,
            surface,
        }
    }
}

/// A closed triangle mesh: counter-clockwise seen from outside, unit outward normals, UVs in
/// metres.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct Surface {
    pub(super) positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    pub(super) uvs: Vec<Vec2>,
    pub(super) indices: Vec<u32>,
}

impl Surface {
    /// The surface moved by a rigid `placement`.
    fn placed(mut self, placement: Affine3A) -> Self {
        for p in &mut self.positions {
            *p = placement.transform_point3(*p);
        }
        for n in &mut self.normals {
            *n = placement.transform_vector3(*n);
        }
        self
    }
}

/// Every part but the head's, at rest.
fn body_parts(b: &Build, look: &Look) -> Vec<Part> {
    use BodyMaterial::{Shoes, Skin, Top, Trousers};
    let r = |rx, ry| look.radii([rx, ry]);
    let sleeve = if look.short_sleeves { Skin } else { Top };
    let legwear = if look.shorts { Skin } else { Trousers };
    let mut parts = vec![
        Part::new(Bone::Pelvis, Trousers, pelvis(b, look)),
        Part::new(Bone::Chest, Top, chest(b, look)),
        Part::new(Bone::Chest, Skin, neck(b, look)),
    ];
    for side in Side::BOTH {
        parts.extend([
            Part::new(
                Bone::UpperArm(side),
                Top,
                limb(
                    b.upper_arm,
                    [r(0.048, 0.046), r(0.043, 0.041), r(0.036, 0.036)],
                    0.5,
                ),
            ),
            Part::new(
                Bone::Forearm(side),
                sleeve,
                limb(
                    b.forearm,
                    [look.radii(FOREARM), r(0.036, 0.033), r(0.03, 0.022)],
                    0.35,
                ),
            ),
            Part::new(Bone::Forearm(side), Skin, hexahedron(b.hand_corners(look))),
            Part::new(
                Bone::Thigh(side),
                Trousers,
                limb(
                    b.thigh,
                    [r(0.085, 0.075), r(0.07, 0.064), r(0.054, 0.05)],
                    0.45,
                ),
            ),
            Part::new(
                Bone::Shin(side),
                legwear,
                limb(
                    b.shin,
                    [r(0.052, 0.05), r(0.058, 0.05), r(0.037, 0.034)],
                    0.3,
                ),
            ),
            Part::new(Bone::Foot(side), Shoes, hexahedron(b.foot_corners())),
        ]);
    }
    parts
}

/// Hips and belly, from the crotch to above the waist, about the hip joints.
fn pelvis(b: &Build, look: &Look) -> Surface {
    let w = b.waist;
    let r = |rx, ry| look.radii([rx, ry]);
    let rings = [
        Ring::pole(-0.75 * w),
        Ring::new(-0.62 * w, r(0.06, 0.1)),
        Ring::new(-0.3 * w, r(0.095, 0.15)),
        Ring::new(0.0, look.radii(HIPS)),
        Ring::new(0.5 * w, r(0.098, 0.155)),
        Ring::new(w, r(0.088, 0.14)),
        Ring::new(1.25 * w, r(0.07, 0.112)),
        Ring::pole(1.35 * w),
    ];
    lathe(&rings, TORSO_SIDES)
}

/// Waist, ribs and shoulders, about the waist.
fn chest(b: &Build, look: &Look) -> Surface {
    let s = b.shoulder;
    let r = |rx, ry| look.radii([rx, ry]);
    let broad = |rx, ry| look.radii([rx, ry * look.shoulders]);
    let rings = [
        Ring::pole(-0.18 * s),
        Ring::new(-0.12 * s, r(0.075, 0.12)),
        Ring::new(0.0, r(0.088, 0.138)),
        Ring::new(0.35 * s, r(0.098, 0.148)),
        Ring::new(0.68 * s, broad(0.105, 0.158)),
        Ring::new(0.92 * s, broad(0.098, 0.168)),
        Ring::new(1.06 * s, broad(0.075, 0.165)),
        Ring::new(1.16 * s, r(0.045, 0.095)),
        Ring::pole(1.2 * s),
    ];
    lathe(&rings, TORSO_SIDES)
}

/// The neck, from inside the chest to inside the head, in the chest frame.
fn neck(b: &Build, look: &Look) -> Surface {
    let radius = 0.052 * look.scale * look.girth.sqrt();
    let (bottom, top) = (b.shoulder - 0.03 * look.scale, b.head - 0.05 * look.scale);
    let rings = [
        Ring::pole(bottom - 0.3 * radius),
        Ring::new(bottom, Vec2::splat(radius)),
        Ring::new(top, Vec2::splat(0.95 * radius)),
        Ring::pole(top + 0.3 * radius),
    ];
    lathe(&rings, LIMB_SIDES)
}

/// The head (an ellipsoid tilted back) and the hair capping its crown and back, about the
/// head's centre.
fn head_parts(look: &Look) -> [Part; 2] {
    let radii = look.head;
    let tilt = Affine3A::from_quat(Quat::from_rotation_y(-HEAD_TILT));
    let latitudes = |from: f32, count: usize| {
        (1..count).map(move |k| from + (FRAC_PI_2 - from) * k as f32 / count as f32)
    };
    let head: Vec<Ring> = once(Ring::pole(-radii.z))
        .chain(latitudes(-FRAC_PI_2, 8).map(|lat| Ring::on_ellipsoid(radii, lat, 0.0)))
        .chain(once(Ring::pole(radii.z)))
        .collect();
    let hairline = (look.hairline / radii.z).asin();
    // The hair's underside is a cone inside the head.
    let hair: Vec<Ring> = once(Ring::pole(look.hairline - 0.2 * radii.z))
        .chain(once(Ring::on_ellipsoid(radii, hairline, look.hair)))
        .chain(latitudes(hairline, 4).map(|lat| Ring::on_ellipsoid(radii, lat, look.hair)))
        .chain(once(Ring::pole(radii.z + look.hair)))
        .collect();
    [
        Part::new(
            Bone::Head,
            BodyMaterial::Skin,
            lathe(&head, TORSO_SIDES).placed(tilt),
        ),
        Part::new(
            Bone::Head,
            BodyMaterial::Hair,
            lathe(&hair, TORSO_SIDES).placed(tilt),
        ),
    ]
}

/// A limb of `length` hanging from its joint along −z, with elliptic cross-sections of radii
/// `[top, middle, bottom]` (the middle one `middle_at` of the way down) and rounded ends
/// that reach past both joints.
fn limb(length: f32, [top, middle, bottom]: [Vec2; 3], middle_at: f32) -> Surface {
    let dome = |r: Vec2| 0.5 * (r.x + r.y);
    let rings = [
        Ring::pole(-length - 0.9 * dome(bottom)),
        Ring::new(-length - 0.6 * dome(bottom), 0.75 * bottom),
        Ring::new(-length, bottom),
        Ring::new(-middle_at * length, middle),
        Ring::new(0.0, top),
        Ring::new(0.6 * dome(top), 0.75 * top),
        Ring::pole(0.9 * dome(top)),
    ];
    lathe(&rings, LIMB_SIDES)
}

/// One cross-section of a [`lathe`]: an ellipse about the z axis.
#[derive(Clone, Copy, Debug)]
struct Ring {
    z: f32,
    /// Semi-axes along x and y; zero at a pole.
    radii: Vec2,
}

impl Ring {
    fn new(z: f32, radii: Vec2) -> Self {
        Self { z, radii }
    }

    fn pole(z: f32) -> Self {
        Self::new(z, Vec2::ZERO)
    }

    /// The ring at `latitude` of an ellipsoid of semi-axes `radii`, grown by `grow`.
    fn on_ellipsoid(radii: Vec3, latitude: f32, grow: f32) -> Self {
        let (sin, cos) = latitude.sin_cos();
        Self::new((radii.z + grow) * sin, (radii.truncate() + grow) * cos)
    }

    /// The point of the ring at `angle` about z.
    fn point(&self, angle: f32) -> Vec3 {
        let (sin, cos) = angle.sin_cos();
        Vec3::new(self.radii.x * cos, self.radii.y * sin, self.z)
    }
}

/// A closed surface through `rings` by rising z (the first and last are its poles), each ring
/// an ellipse of `sides` corners: smooth normals, u around each ring and v along the profile in
/// metres, the UV seam at the back (−x).
fn lathe(rings: &[Ring], sides: usize) -> Surface {
    let last = rings.len() - 1;
    let is_pole = |k: usize| k == 0 || k == last;
    // A pole has a copy per side (each with its own u), a ring a copy of its first corner at
    // the seam.
    let columns = |k: usize| if is_pole(k) { sides } else { sides + 1 };
    let angle = |j: usize| PI + TAU * (j % sides) as f32 / sides as f32;
    let starts: Vec<usize> = (0..=last)
        .scan(0, |next, k| {
            let start = *next;
            *next += columns(k);
            Some(start)
        })
        .collect();
    let mut surface = Surface::default();
    // The first copy of each vertex: normals gather there.
    let mut welded = Vec::new();
    let mut v = 0.0;
    for (k, ring) in rings.iter().enumerate() {
        if k > 0 {
            let below = rings[k - 1];
            let mean = |r: Ring| 0.5 * (r.radii.x + r.radii.y);
            v += Vec2::new(ring.z - below.z, mean(*ring) - mean(below)).length();
        }
        let around = arc_lengths(&rings[k.clamp(1, last - 1)], sides, angle);
        for j in 0..columns(k) {
            let u = if is_pole(k) {
                0.5 * (around[j] + around[j + 1])
            } else {
                around[j]
            };
            surface.positions.push(ring.point(angle(j)));
            surface.uvs.push(Vec2::new(u, v));
            welded.push(starts[k] + if is_pole(k) { 0 } else { j % sides });
        }
    }
    // Each band between two rings is a strip of quads (lower j, lower j + 1, upper j + 1,
    // upper j), one triangle of each where the band meets a pole.
    for k in 0..last {
        let lower = |j: usize| (starts[k] + j) as u32;
        let upper = |j: usize| (starts[k + 1] + j) as u32;
        for j in 0..sides {
            if k != 0 {
                let apex = if k + 1 == last {
                    upper(j)
                } else {
                    upper(j + 1)
                };
                surface.indices.extend([lower(j), lower(j + 1), apex]);
            }
            if k + 1 != last {
                surface.indices.extend([lower(j), upper(j + 1), upper(j)]);
            }
        }
    }
    surface.normals = welded_normals(&surface.positions, &surface.indices, &welded);
    surface
}

/// Distance around `ring` from its first corner to each corner and back to the first.
fn arc_lengths(ring: &Ring, sides: usize, angle: impl Fn(usize) -> f32) -> Vec<f32> {
    once(0.0)
        .chain((0..sides).scan(0.0, |total, j| {
            *total += ring.point(angle(j)).distance(ring.point(angle(j + 1)));
            Some(*total)
        }))
        .collect()
}

/// Area-weighted vertex normals, shared by the copies of each vertex (`welded[i]` is the first
/// copy of vertex `i`).
fn welded_normals(positions: &[Vec3], indices: &[u32], welded: &[usize]) -> Vec<Vec3> {
    let mut sums = vec![Vec3::ZERO; positions.len()];
    for triangle in indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|i| triangle[i] as usize);
        let normal = (positions[b] - positions[a]).cross(positions[c] - positions[a]);
        for i in [a, b, c] {
            sums[welded[i]] += normal;
        }
    }
    welded.iter().map(|&w| sums[w].normalize()).collect()
}

/// A six-faced solid from its corners (index bits: +x end, +y side, top), each face flat and
/// planar, with UVs in metres along its edges.
pub(super) fn hexahedron(corners: [Vec3; 8]) -> Surface {
    const FACES: [[usize; 4]; 6] = [
        [0, 2, 6, 4],
        [1, 3, 7, 5],
        [0, 1, 5, 4],
        [2, 3, 7, 6],
        [0, 1, 3, 2],
        [4, 5, 7, 6],
    ];
    let centre = corners.iter().sum::<Vec3>() / 8.0;
    let mut surface = Surface::default();
    for face in FACES {
        let mut quad = face.map(|i| corners[i]);
        let outward = quad.iter().sum::<Vec3>() / 4.0 - centre;
        if (quad[2] - quad[0]).cross(quad[3] - quad[1]).dot(outward) < 0.0 {
            quad.reverse();
        }
        let normal = (quad[2] - quad[0]).cross(quad[3] - quad[1]).normalize();
        let across = (quad[1] - quad[0]).normalize();
        let up = normal.cross(across);
        let base = surface.positions.len() as u32;
        for p in quad {
            surface.positions.push(p);
            surface.normals.push(normal);
            surface
                .uvs
                .push(Vec2::new((p - quad[0]).dot(across), (p - quad[0]).dot(up)));
        }
        surface
            .indices
            .extend([base, base + 1, base + 2, base, base + 2, base + 3]);
    }
    surface
}

#[cfg(test)]
mod tests {
    use std::collections::HashMap;

    use super::*;

    const STRIDES: [f32; 4] = [0.0, 0.4, 0.7, MAX_STRIDE];
    const SEEDS: std::ops::Range<u64> = 0..6;

    fn body(seed: u64) -> WalkerBody {
        WalkerBody::new(&mut Rng::new(seed))
    }

    fn posed(body: &WalkerBody, phase: f32, stride: f32) -> PosedMesh {
        let mut mesh = PosedMesh::default();
        body.pose(phase, stride, &mut mesh);
        mesh
    }

    /// 64 phases over a cycle.
    fn phases() -> impl Iterator<Item = f32> {
        (0..64).map(|i| i as f32 / 64.0)
    }

    /// Indices of the vertices of `side`'s shoe.
    fn shoe(mesh: &PosedMesh, side: Side) -> Vec<usize> {
        (0..mesh.positions.len())
            .filter(|&i| mesh.materials[i] == BodyMaterial::Shoes)
            .filter(|&i| mesh.positions[i].y * side.sign() > 0.0)
            .collect()
    }

    fn centroid(mesh: &PosedMesh, vertices: &[usize]) -> Vec3 {
        vertices.iter().map(|&i| mesh.positions[i]).sum::<Vec3>() / vertices.len() as f32
    }

    /// Knee flexion of `side`, radians.
    fn knee(skeleton: &Skeleton, side: Side) -> f32 {
        let [thigh, shin, _] = skeleton.legs[side as usize];
        let cos = thigh.matrix3.z_axis.dot(shin.matrix3.z_axis);
        cos.clamp(-1.0, 1.0).acos()
    }

    /// Hip flexion of `side` (thigh ahead of the vertical positive), radians.
    fn hip(skeleton: &Skeleton, side: Side) -> f32 {
        let up = skeleton.legs[side as usize][0].matrix3.z_axis;
        (-up.x).atan2(up.z)
    }

    /// Where `side`'s hand is.
    fn hand(body: &WalkerBody, skeleton: &Skeleton, side: Side) -> Vec3 {
        body.palms(skeleton)[side as usize]
    }

    #[test]
    fn every_vertex_stays_within_a_stride_and_under_the_stature() {
        for seed in SEEDS {
            let body = body(seed);
            for stride in STRIDES {
                let mut widest = 0.0f32;
                for phase in phases() {
                    for p in posed(&body, phase, stride).positions {
                        widest = widest.max(p.truncate().length());
                        // Heel to toe, a step and a shoe at most; shoulders and arms at most
                        // 0.4 m from the axis sideways.
                        assert!(
                            p.x.abs() <= stride / 2.0 + 0.35 && p.y.abs() <= 0.4,
                            "seed {seed} stride {stride} phase {phase}: {p} too far out"
                        );
                        assert!(p.z <= body.height() + 1e-3, "{p} over {}", body.height());
                    }
                }
                if stride == 0.0 {
                    assert!((0.2..0.35).contains(&widest), "standing, {widest} wide");
                }
            }
        }
    }

    #[test]
    fn the_stature_is_the_top_of_the_standing_body() {
        for seed in SEEDS {
            let body = body(seed);
            assert!((1.55..1.90).contains(&body.height()));
            let top = posed(&body, 0.3, 0.0)
                .positions
                .iter()
                .map(|p| p.z)
                .fold(f32::MIN, f32::max);
            assert!(
                (top - body.height()).abs() < 1e-3,
                "top {top}, stature {}",
                body.height()
            );
        }
    }

    #[test]
    fn soles_touch_the_floor_and_nothing_sinks_below_it() {
        for seed in SEEDS {
            let body = body(seed);
            for stride in STRIDES {
                for phase in phases() {
                    let mesh = posed(&body, phase, stride);
                    let lowest = |side| {
                        shoe(&mesh, side)
                            .iter()
                            .map(|&i| mesh.positions[i].z)
                            .fold(f32::MAX, f32::min)
                    };
                    let (left, right) = (lowest(Side::Left), lowest(Side::Right));
                    let floor = mesh.positions.iter().map(|p| p.z).fold(f32::MAX, f32::min);
                    assert!(
                        floor >= -1e-3,
                        "seed {seed} stride {stride} phase {phase}: {floor}"
                    );
                    assert!(
                        left.min(right) < 0.02,
                        "stride {stride} phase {phase}: both feet up"
                    );
                    if stride == 0.0 {
                        assert!(
                            left.max(right).abs() < 1e-4,
                            "standing on {left} and {right}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn a_planted_foot_keeps_its_place_on_the_floor() {
        let (body, stride) = (body(3), 0.7);
        // The body frame moves 2 * stride per cycle over the floor.
        let on_floor = |phase: f32| {
            let mesh = posed(&body, phase, stride);
            let sole: Vec<Vec3> = shoe(&mesh, Side::Left)
                .into_iter()
                .map(|i| mesh.positions[i])
                .filter(|p| p.z.abs() < 1e-3)
                .map(|p| p + Vec3::X * 2.0 * stride * phase)
                .collect();
            sole
        };
        let flat = on_floor(0.2);
        assert_eq!(
            flat.len(),
            12,
            "a flat sole has four corners, three copies each"
        );
        for i in 0..=48 {
            let phase = STANCE * i as f32 / 48.0;
            let touching = on_floor(phase);
            assert!(
                !touching.is_empty(),
                "phase {phase}: left foot off the floor in its stance"
            );
            for p in touching {
                let slid = flat.iter().map(|q| q.distance(p)).fold(f32::MAX, f32::min);
                assert!(slid < 1e-3, "phase {phase}: the sole slid {slid} m");
            }
        }
    }

    #[test]
    fn a_swinging_foot_leaves_and_meets_the_floor_at_rest() {
        let (body, stride) = (body(3), 0.7);
        // Where the left ankle is over the floor, which the body frame crosses at 2 * stride a
        // cycle.
        let ankle = |phase: f32| {
            let ankle = body.skeleton(phase, stride).legs[0][2].translation;
            ankle.x + 2.0 * stride * phase
        };
        let dt = 0.005;
        // Swinging, the foot crosses the floor at 2 * stride per swing on average.
        let average = 2.0 * stride / (1.0 - STANCE) * dt;
        for (from, to) in [(STANCE, STANCE + dt), (1.0 - dt, 1.0)] {
            let moved = (ankle(to) - ankle(from)).abs();
            assert!(
                moved < 0.1 * average,
                "{from}..{to}: {moved} m over the floor"
            );
        }
    }

    #[test]
    fn feet_alternate_about_a_step_apart() {
        for seed in SEEDS {
            let body = body(seed);
            for stride in [0.4, 0.7, MAX_STRIDE] {
                let ahead = |phase| {
                    let mesh = posed(&body, phase, stride);
                    let foot = |side| centroid(&mesh, &shoe(&mesh, side));
                    foot(Side::Left).x - foot(Side::Right).x
                };
                let (left, right) = (ahead(0.0), -ahead(0.5));
                for apart in [left, right] {
                    assert!(
                        (apart - stride).abs() < 0.4 * stride,
                        "seed {seed}: feet {apart} m apart at heel strike, step {stride}"
                    );
                }
                // Halfway between the heel strikes the swinging foot is passing the planted
                // one; by the next heel strike it is well past.
                for phase in [0.25, 0.75] {
                    assert!(
                        ahead(phase).abs() < 0.5 * stride,
                        "phase {phase}: {}",
                        ahead(phase)
                    );
                }
                assert!(ahead(0.4) < -0.3 * stride && ahead(0.9) > 0.3 * stride);
            }
        }
    }

    #[test]
    fn arms_swing_against_the_legs() {
        let body = body(5);
        for stride in [0.4, 0.7, MAX_STRIDE] {
            for phase in [0.0, 0.1, 0.4, 0.5, 0.6, 0.9] {
                let skeleton = body.skeleton(phase, stride);
                let hands =
                    hand(&body, &skeleton, Side::Left).x - hand(&body, &skeleton, Side::Right).x;
                let feet = skeleton.legs[0][2].translation.x - skeleton.legs[1][2].translation.x;
                assert!(
                    hands * feet < 0.0,
                    "phase {phase}: hands {hands}, feet {feet}"
                );
            }
        }
        let standing = body.skeleton(0.0, 0.0);
        let left = hand(&body, &standing, Side::Left);
        let right = hand(&body, &standing, Side::Right);
        assert!((left.x - right.x).abs() < 1e-5 && (left.y + right.y).abs() < 1e-5);
    }

    /// Carrying, at every phase of a walk the box lies level between the palms (each palm at
    /// its side, within the grip, between its bottom and top), in front of the chest, and the
    /// arms hold still while the legs walk.
    #[test]
    fn a_carried_box_stays_between_the_palms() {
        for seed in SEEDS {
            let body = WalkerBody::new(&mut Rng::new(seed)).carrying(&mut Rng::new(seed + 100));
            let size = body.carton.unwrap();
            assert!(
                (0.25..0.7).contains(&size.y),
                "seed {seed}: box {size} wide"
            );
            let first = body.skeleton(0.0, USUAL_STRIDE);
            for phase in phases() {
                let skeleton = body.skeleton(phase, USUAL_STRIDE);
                let mesh = posed(&body, phase, USUAL_STRIDE);
                let carton: Vec<Vec3> = (mesh.positions.iter().zip(&mesh.materials))
                    .filter(|(_, &m)| m == BodyMaterial::Carton)
                    .map(|(&p, _)| p)
                    .collect();
                assert_eq!(carton.len(), 24, "a box of six faces");
                let centre = carton.iter().sum::<Vec3>() / 24.0;
                let chest = skeleton.chest.translation;
                assert!(
                    centre.x - size.x / 2.0 > chest.x + 0.1,
                    "phase {phase}: box in the chest"
                );
                let (bottom, top) = (centre.z - size.z / 2.0, centre.z + size.z / 2.0);
                let (_, turn, _) = skeleton.chest.to_scale_rotation_translation();
                let yaw = turn.to_euler(glam::EulerRot::ZYX).0;
                for palm in body.palms(&skeleton) {
                    let local = Quat::from_rotation_z(-yaw) * (palm - centre);
                    let side_gap = local.y.abs() - size.y / 2.0;
                    assert!(
                        (side_gap - CARTON_GRIP / 2.0).abs() < 1e-3,
                        "phase {phase}: palm {side_gap} m off the box's side"
                    );
                    assert!(
                        local.x.abs() < size.x / 2.0,
                        "phase {phase}: palm beyond the box"
                    );
                    assert!(
                        (bottom..top).contains(&palm.z),
                        "phase {phase}: palm at {}",
                        palm.z
                    );
                }
                let arm = |s: &Skeleton| s.arms[0][1].matrix3.z_axis;
                assert!(
                    arm(&skeleton).angle_between(arm(&first)) < 0.2,
                    "phase {phase}: arm swings"
                );
            }
        }
    }

    /// The least and most of `f`, in degrees, over the phases in `range` (of [`phases`],
    /// whose skeletons are `skeletons`).
    fn degrees_over(
        skeletons: &[Skeleton],
        range: std::ops::Range<f32>,
        f: impl Fn(&Skeleton) -> f32,
    ) -> (f32, f32) {
        phases()
            .zip(skeletons)
            .filter(|(phase, _)| range.contains(phase))
            .map(|(_, s)| f(s).to_degrees())
            .fold((f32::MAX, f32::MIN), |(lo, hi), x| (lo.min(x), hi.max(x)))
    }

    #[test]
    fn the_gait_bends_the_joints_like_a_walk() {
        for seed in SEEDS {
            let body = body(seed);
            let stride = USUAL_STRIDE;
            let skeletons: Vec<Skeleton> = phases().map(|p| body.skeleton(p, stride)).collect();
            let left_knee = |s: &Skeleton| knee(s, Side::Left);
            let (_, swing_knee) = degrees_over(&skeletons, STANCE..1.0, left_knee);
            let (_, loading_knee) = degrees_over(&skeletons, 0.0..LOADING_END, left_knee);
            let (mid_stance_knee, _) = degrees_over(&skeletons, 0.2..0.4, left_knee);
            let (strike_knee, _) = degrees_over(&skeletons, 0.0..0.01, left_knee);
            assert!(
                (50.0..68.0).contains(&swing_knee),
                "swing knee {swing_knee}"
            );
            assert!(
                (12.0..25.0).contains(&loading_knee),
                "loading knee {loading_knee}"
            );
            assert!(mid_stance_knee < 8.0, "mid-stance knee {mid_stance_knee}");
            assert!(strike_knee < 8.0, "knee at heel strike {strike_knee}");

            let left_hip = |s: &Skeleton| hip(s, Side::Left);
            let (_, strike_hip) = degrees_over(&skeletons, 0.0..0.01, left_hip);
            let (extension, _) = degrees_over(&skeletons, 0.0..1.0, left_hip);
            let legs = body.build.thigh + body.build.shin;
            let expected = (stride / (2.0 * legs)).asin().to_degrees();
            assert!(
                (strike_hip - expected).abs() < 6.0,
                "hip {strike_hip}, {expected} expected"
            );
            assert!(
                (-20.0..-5.0).contains(&extension),
                "hip extension {extension}"
            );

            let (_, arm) = degrees_over(&skeletons, 0.0..1.0, |s| {
                let up = s.arms[Side::Left as usize][0].matrix3.z_axis;
                (-up.x).atan2(up.z)
            });
            assert!((10.0..25.0).contains(&arm), "arm swing {arm}");

            // The pelvis bobs twice a cycle, lowest about when both feet are down.
            let heights: Vec<f32> = skeletons.iter().map(|s| s.pelvis.translation.z).collect();
            let top = heights.iter().copied().fold(f32::MIN, f32::max);
            for step in [0..32, 32..64] {
                let (low, at) = step
                    .map(|i| (heights[i], (i % 32) as f32 / 64.0))
                    .fold((f32::MAX, 0.0), |a, b| if b.0 < a.0 { b } else { a });
                assert!((0.02..0.08).contains(&(top - low)), "bob {}", top - low);
                assert!(!(0.1..0.4).contains(&at), "lowest {at} cycles into a step");
            }
        }
    }

    #[test]
    fn standing_still_is_a_still_upright_pose() {
        let body = body(2);
        let standing = posed(&body, 0.0, 0.0);
        assert_eq!(standing.positions, posed(&body, 0.37, 0.0).positions);
        let skeleton = body.skeleton(0.0, 0.0);
        for side in Side::BOTH {
            assert!(knee(&skeleton, side).to_degrees() < 4.0);
            // Thigh and shin share the slight bend of the knee.
            assert!((hip(&skeleton, side) - 0.5 * STRAIGHT_KNEE).abs() < 1e-3);
        }
    }

    #[test]
    fn every_part_is_a_closed_surface_facing_out() {
        for seed in 0..3 {
            let body = body(seed);
            for (phase, stride) in [(0.0, 0.0), (0.37, 0.7), (0.81, MAX_STRIDE)] {
                let mesh = posed(&body, phase, stride);
                for n in &mesh.normals {
                    assert!((n.length() - 1.0).abs() < 1e-4, "normal {n}");
                }
                let triangles: Vec<[usize; 3]> = mesh
                    .indices
                    .chunks_exact(3)
                    .map(|t| [t[0], t[1], t[2]].map(|i| i as usize))
                    .collect();
                // The parts' vertices follow each other in the order of the body's parts.
                let mut start = 0;
                let mut checked = 0;
                for part in &body.parts {
                    let vertices = start..start + part.surface.positions.len();
                    let own: Vec<[usize; 3]> = triangles
                        .iter()
                        .filter(|t| vertices.contains(&t[0]))
                        .copied()
                        .collect();
                    assert!(own.iter().flatten().all(|i| vertices.contains(i)));
                    check_closed_and_outward(&mesh, &welded(&mesh, vertices.clone()), &own);
                    checked += own.len();
                    start = vertices.end;
                }
                assert_eq!((start, checked), (mesh.positions.len(), triangles.len()));
            }
        }
    }

    /// For each vertex of `vertices`, the first of them at its position: copies of a vertex
    /// (along a UV seam, at a pole, at a corner of a flat-shaded box) share it.
    fn welded(mesh: &PosedMesh, vertices: std::ops::Range<usize>) -> HashMap<usize, usize> {
        let mut first = HashMap::new();
        let key = |i: usize| mesh.positions[i].to_array().map(f32::to_bits);
        vertices
            .map(|i| (i, *first.entry(key(i)).or_insert(i)))
            .collect()
    }

    /// Every edge of `triangles` (between welded vertices) is met once each way (closed and
    /// consistently wound), they enclose a positive volume (counter-clockwise seen from
    /// outside), and the normals point out: along their triangles' and away from the part's
    /// centre.
    fn check_closed_and_outward(
        mesh: &PosedMesh,
        weld: &HashMap<usize, usize>,
        triangles: &[[usize; 3]],
    ) {
        let p = |i: usize| mesh.positions[i];
        let mut edges: HashMap<(usize, usize), usize> = HashMap::new();
        let mut volume = 0.0;
        for &[a, b, c] in triangles {
            let [wa, wb, wc] = [a, b, c].map(|i| weld[&i]);
            for edge in [(wa, wb), (wb, wc), (wc, wa)] {
                *edges.entry(edge).or_default() += 1;
            }
            volume += p(a).dot(p(b).cross(p(c))) / 6.0;
        }
        for (&(a, b), &count) in &edges {
            assert_eq!(count, 1, "edge {a}-{b} met {count} times one way");
            assert_eq!(edges.get(&(b, a)), Some(&1), "edge {a}-{b} open");
        }
        assert!(volume > 0.0, "a part turned inside out: volume {volume}");
        let corners: Vec<usize> = triangles.iter().flatten().copied().collect();
        let centre = corners.iter().map(|&i| p(i)).sum::<Vec3>() / corners.len() as f32;
        let inward = corners
            .iter()
            .filter(|&&i| mesh.normals[i].dot(p(i) - centre) <= 0.0)
            .count();
        assert!(
            inward * 50 < corners.len(),
            "{inward} of {} normals face in",
            corners.len()
        );
        for &[a, b, c] in triangles {
            let face = (p(b) - p(a)).cross(p(c) - p(a));
            for i in [a, b, c] {
                assert!(
                    mesh.normals[i].dot(face) > 0.0,
                    "a normal against its triangle: {:?} {} at {}",
                    mesh.materials[i],
                    mesh.normals[i],
                    p(i)
                );
            }
        }
    }

    #[test]
    fn posing_appends_and_repeats_exactly() {
        let body = body(4);
        let mut mesh = posed(&body, 0.3, 0.6);
        let n = mesh.positions.len();
        let triangles = mesh.indices.len() / 3;
        assert!((500..=2000).contains(&triangles), "{triangles} triangles");
        body.pose(0.3, 0.6, &mut mesh);
        assert_eq!(mesh.positions[n..], mesh.positions[..n]);
        assert_eq!(mesh.normals[n..], mesh.normals[..n]);
        assert_eq!(mesh.uvs[n..], mesh.uvs[..n]);
        assert_eq!(mesh.materials[n..], mesh.materials[..n]);
        let (first, second) = mesh.indices.split_at(3 * triangles);
        assert!(first.iter().zip(second).all(|(a, b)| b - a == n as u32));
        assert!(mesh.indices.iter().all(|&i| (i as usize) < 2 * n));
        for material in [
            BodyMaterial::Top,
            BodyMaterial::Trousers,
            BodyMaterial::Skin,
            BodyMaterial::Hair,
            BodyMaterial::Shoes,
        ] {
            assert!(mesh.materials.contains(&material), "no {material:?}");
        }
    }

    #[test]
    fn a_lathe_is_smooth_across_its_seam_and_at_its_poles() {
        let radii = Vec3::new(1.0, 1.0, 1.0);
        let rings: Vec<Ring> = once(Ring::pole(-1.0))
            .chain((1..8).map(|k| Ring::on_ellipsoid(radii, PI * k as f32 / 8.0 - FRAC_PI_2, 0.0)))
            .chain(once(Ring::pole(1.0)))
            .collect();
        let sphere = lathe(&rings, TORSO_SIDES);
        for (i, p) in sphere.positions.iter().enumerate() {
            assert!(
                sphere.normals[i].dot(p.normalize()) > 0.99,
                "{p}: {}",
                sphere.normals[i]
            );
            for (j, q) in sphere.positions.iter().enumerate() {
                if p == q {
                    assert_eq!(sphere.normals[i], sphere.normals[j], "copies of {p}");
                }
            }
        }
    }

    #[test]
    fn uvs_measure_metres_around_a_limb() {
        let body = body(6);
        let thigh = body
            .parts
            .iter()
            .find(|p| p.bone == Bone::Thigh(Side::Left))
            .expect("a thigh");
        let uvs = &thigh.surface.uvs;
        let around = uvs.iter().map(|uv| uv.x).fold(0.0, f32::max);
        let along = uvs.iter().map(|uv| uv.y).fold(0.0, f32::max);
        // An ellipse of about 8 cm radius, and a thigh with its rounded ends.
        assert!((0.4..0.6).contains(&around), "{around} m around");
        assert!(
            (body.build.thigh..body.build.thigh + 0.2).contains(&along),
            "{along} m along"
        );
    }

    #[test]
    fn the_same_seed_gives_the_same_body_and_seeds_vary_it() {
        assert_eq!(body(7), body(7));
        let statures: Vec<f32> = (0..12).map(|seed| body(seed).height()).collect();
        for (i, a) in statures.iter().enumerate() {
            assert!(statures[i + 1..].iter().all(|b| b != a), "{statures:?}");
        }
        let spread = statures.iter().fold(f32::MIN, |m, &s| m.max(s))
            - statures.iter().fold(f32::MAX, |m, &s| m.min(s));
        assert!(spread > 0.15, "{statures:?}");
    }
}
