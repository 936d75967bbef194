//! The simulator: a world, a Pioneer 2-DX, its sonar ring and its drifting odometry.
//!
//! Each [`Simulator::step`] advances the true pose under the current command (Stage's
//! 100 ms tick by default), updates the believed pose from noisy odometry and reads all 16
//! sonars at the new true pose, as Stage does at 10 Hz.
//!
//! The believed pose starts equal to the true start pose, so belief and truth share one frame
//! (the world's) and the position error is simply the distance between them.
//!
//! Determinism: one run seed gives three independent random streams ([`Streams`]): drift,
//! sensing and behaviour. The true path depends only on the commands; the drift stream is
//! consumed identically whatever the believed pose is; and [`Simulator::set_odometry`] draws
//! nothing. So a controller that reacts only to sonar (and the behaviour stream) drives the same
//! true path for a seed whether or not the SLAM rules reset the odometry.

use super::geom::Pose;
use super::odometry::{Biases, DriftParams, Odometry};
use super::pioneer::{Motion, Pioneer};
use super::rng::{Rng, Streams};
use super::sonar::{SonarModel, NUM_SONARS};
use super::world::World;

/// What one step produced.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SimStep {
    /// Simulated time after the step, s.
    pub time_s: f64,
    /// True pose after the step.
    pub true_pose: Pose,
    /// Believed (odometry) pose after the step.
    pub believed: Pose,
    /// The 16 sonar ranges at the new true pose, mm.
    pub ranges_mm: [f64; NUM_SONARS],
    /// What the body did (distance, rotation, stall).
    pub motion: Motion,
}

/// A seeded simulation of one robot in one world.
#[derive(Debug, Clone)]
pub struct Simulator {
    world: World,
    robot: Pioneer,
    sonar: SonarModel,
    odometry: Odometry,
    sensing: Rng,
    behaviour: Rng,
    drift: Rng,
    time_s: f64,
    steps: u64,
}

impl Simulator {
    /// A simulator for `world` with its noise preset, Stage 2 odometry drift and run `seed`.
    pub fn new(world: World, seed: u64) -> Self {
        let sonar = SonarModel::preset(world.run.noise);
        Simulator::with_models(world, seed, sonar, DriftParams::STAGE2)
    }

    /// A simulator with explicit sonar and drift models.
    pub fn with_models(world: World, seed: u64, sonar: SonarModel, drift: DriftParams) -> Self {
        let mut streams = Streams::from_seed(seed);
        let odometry = Odometry::new(drift, world.start, &mut streams.drift);
        Simulator {
            robot: Pioneer::new(world.start),
            world,
            sonar,
            odometry,
            sensing: streams.sensing,
            behaviour: streams.behaviour,
            drift: streams.drift,
            time_s: 0.0,
            steps: 0,
        }
    }

    /// The world.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The sonar model in use.
    pub fn sonar_model(&self) -> &SonarModel {
        &self.sonar
    }

    /// This run's odometry biases.
    pub fn biases(&self) -> Biases {
        self.odometry.biases()
    }

    /// Simulated time, s.
    pub fn time_s(&self) -> f64 {
        self.time_s
    }

    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// The true pose.
    pub fn true_pose(&self) -> Pose {
        self.robot.pose()
    }

    /// The believed pose.
    pub fn believed(&self) -> Pose {
        self.odometry.believed()
    }

    /// The robot body (commanded velocities, stall flag).
    pub fn robot(&self) -> &Pioneer {
        &self.robot
    }

    /// The behaviour stream, for the wander controller's random choices.
    pub fn behaviour_rng(&mut self) -> &mut Rng {
        &mut self.behaviour
    }

    /// Sets the translational velocity, mm/s.
    pub fn set_vel_mm_s(&mut self, v: f64) {
        self.robot.set_vel_mm_s(v);
    }

    /// Sets the rotational velocity, °/s.
    pub fn set_rot_vel_deg_s(&mut self, w: f64) {
        self.robot.set_rot_vel_deg_s(w);
    }

    /// Stops the robot.
    pub fn stop(&mut self) {
        self.robot.stop();
    }

    /// Overwrites the believed pose (the thesis's `setOdometry`); the true pose is untouched.
    pub fn set_odometry(&mut self, pose: Pose) {
        self.odometry.set_odometry(pose);
    }

    /// `setOdometry` in the thesis's units: mm, mm, degrees.
    pub fn set_odometry_mm_deg(&mut self, x_mm: f64, y_mm: f64, th_deg: f64) {
        self.set_odometry(Pose::from_mm_deg(x_mm, y_mm, th_deg));
    }

    /// Reads the sonar ring at the current true pose without moving (mm). Uses the sensing
    /// stream, like a step.
    pub fn sense(&mut self) -> [f64; NUM_SONARS] {
        let pose = self.robot.pose();
        self.sonar
            .read_ring_mm(&self.world.walls, &pose, &mut self.sensing)
    }

    /// One step of the world's time step (`world.run.dt`).
    pub fn tick(&mut self) -> SimStep {
        self.step(self.world.run.dt)
    }

    /// Advances the simulation by `dt` seconds (non-finite or negative counts as 0): moves the
    /// body, updates the odometry and reads the sonars.
    pub fn step(&mut self, dt: f64) -> SimStep {
        let dt = if dt.is_finite() { dt.max(0.0) } else { 0.0 };
        let motion = self.robot.step(&self.world.walls, dt);
        self.odometry.update(&motion, &mut self.drift);
        let ranges_mm = self.sense();
        self.time_s += dt;
        self.steps += 1;
        SimStep {
            time_s: self.time_s,
            true_pose: self.robot.pose(),
            believed: self.odometry.believed(),
            ranges_mm,
            motion,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::pioneer::{CRUISE_SPEED_M_S, DEFAULT_DT_S, TURN_RATE_DEG_S};
    use super::super::sonar::NoisePreset;
    use super::*;

    /// A purely sonar-reactive wander: cruise; when a front sonar reads under 0.7 m, turn in
    /// place by a random 90–200° (behaviour stream), then cruise again.
    struct Wander {
        turn_left_deg: f64,
    }

    impl Wander {
        fn act(&mut self, sim: &mut Simulator, ranges: &[f64; NUM_SONARS]) {
            if self.turn_left_deg.abs() > 1e-9 {
                let step = TURN_RATE_DEG_S * DEFAULT_DT_S;
                let d = self.turn_left_deg.clamp(-step, step);
                self.turn_left_deg -= d;
                sim.set_vel_mm_s(0.0);
                sim.set_rot_vel_deg_s(d / DEFAULT_DT_S);
                return;
            }
            let front = ranges[2..=5].iter().copied().fold(f64::INFINITY, f64::min);
            if front < 700.0 {
                let rng = sim.behaviour_rng();
                let angle = rng.range(90.0, 200.0);
                let sign = if rng.chance(0.5) { 1.0 } else { -1.0 };
                self.turn_left_deg = sign * angle;
                sim.stop();
            } else {
                sim.set_vel_mm_s(CRUISE_SPEED_M_S * 1000.0);
                sim.set_rot_vel_deg_s(0.0);
            }
        }
    }

    /// Runs `steps` steps of wander; `reset_every` > 0 calls set_odometry with a junk pose
    /// every that many steps. Returns the true and believed paths.
    fn wander(world: World, seed: u64, steps: usize, reset_every: usize) -> (Vec<Pose>, Vec<Pose>) {
        let mut sim = Simulator::new(world, seed);
        let mut w = Wander { turn_left_deg: 0.0 };
        let mut ranges = sim.sense();
        let (mut truth, mut belief) = (vec![], vec![]);
        for i in 0..steps {
            w.act(&mut sim, &ranges);
            let s = sim.step(DEFAULT_DT_S);
            ranges = s.ranges_mm;
            truth.push(s.true_pose);
            belief.push(s.believed);
            if reset_every > 0 && i % reset_every == 0 {
                sim.set_odometry_mm_deg(i as f64, -(i as f64), i as f64 * 7.0);
            }
        }
        (truth, belief)
    }

    #[test]
    fn same_seed_same_run() {
        let a = wander(World::empty_room(), 5, 600, 0);
        let b = wander(World::empty_room(), 5, 600, 0);
        assert_eq!(a, b);
        let c = wander(World::empty_room(), 6, 600, 0);
        assert_ne!(a.0, c.0);
    }

    #[test]
    fn true_path_ignores_set_odometry() {
        for preset in NoisePreset::ALL {
            let mut world = World::empty_room();
            world.run.noise = preset;
            let (plain, belief_plain) = wander(world.clone(), 11, 1500, 0);
            let (reset, belief_reset) = wander(world, 11, 1500, 37);
            assert_eq!(plain, reset, "true path changed under {preset}");
            assert_ne!(belief_plain, belief_reset);
        }
    }

    #[test]
    fn wander_stays_inside_and_drifts() {
        let world = World::empty_room();
        let (truth, belief) = wander(world, 3, 3000, 0);
        assert!(truth
            .iter()
            .all(|p| p.x.abs() < 4.0 - 0.25 + 1e-9 && p.y.abs() < 3.0 - 0.25 + 1e-9));
        // The robot moved around the room, and the belief drifted away from the truth.
        let span = truth.iter().map(|p| p.x).fold(f64::NEG_INFINITY, f64::max)
            - truth.iter().map(|p| p.x).fold(f64::INFINITY, f64::min);
        assert!(span > 3.0, "x span {span}");
        let last = truth.len() - 1;
        assert!(truth[last].distance(&belief[last]) > 0.01);
    }

    #[test]
    fn step_reports_time_and_ranges() {
        let mut sim = Simulator::new(World::empty_room(), 1);
        sim.set_vel_mm_s(300.0);
        let s = sim.step(0.1);
        assert!((s.time_s - 0.1).abs() < 1e-12);
        assert!((s.true_pose.x - 0.03).abs() < 1e-12);
        assert!((s.motion.distance - 0.03).abs() < 1e-12);
        // Sonar 3 faces +x (10°); its nearest echo in the 8 × 6 m room is about 3.8 m.
        assert!((s.ranges_mm[3] - 3804.0).abs() < 30.0, "{}", s.ranges_mm[3]);
        let s = sim.step(f64::NAN);
        assert_eq!(s.motion, Motion::default());
        assert_eq!(sim.steps(), 2);
    }

    #[test]
    fn tick_uses_the_world_time_step() {
        let mut world = World::empty_room();
        world.run.dt = 0.05;
        let mut sim = Simulator::new(world, 1);
        sim.set_vel_mm_s(200.0);
        let s = sim.tick();
        assert!((s.time_s - 0.05).abs() < 1e-12 && (s.motion.distance - 0.01).abs() < 1e-12);
    }

    #[test]
    fn box_partition_reproduces_thesis_figure_14() {
        // Thesis Figure 14: the robot in the partition box reads (1215, 1510, 2249, 2464, 2464,
        // 2741, 2426, 1965, 1965, 1863, 1395, 1239, 1239, 1395, 1510) from sonars 0–14.
        let thesis = [
            1215.0, 1510.0, 2249.0, 2464.0, 2464.0, 2741.0, 2426.0, 1965.0, 1965.0, 1863.0, 1395.0,
            1239.0, 1239.0, 1395.0, 1510.0,
        ];
        let mut sim = Simulator::new(World::box_partition(), 1);
        let ranges = sim.sense();
        let mut worst = 0.0f64;
        for (i, (got, want)) in ranges.iter().zip(thesis).enumerate() {
            worst = worst.max((got - want).abs());
            assert!(
                (got - want).abs() < 60.0,
                "sonar {i}: {got:.0} vs thesis {want}"
            );
        }
        eprintln!("Figure 14 ranges: worst difference {worst:.0} mm");
    }
}
