//! Soar-SLAM's robot side: the simulated Pioneer 2-DX, its sonar ring and odometry drift, the
//! world it drives in, and the thesis's sonar-to-walls Hough pipeline.
//!
//! - [`world`]: world files (TOML) and the built-in empty room and partition box;
//! - [`pioneer`]: differential-drive body with wall collision;
//! - [`sonar`]: the 16-transducer ring and its noise presets;
//! - [`odometry`]: Stage 2's drift model and the believed pose;
//! - [`sim`]: the [`Simulator`] tying them together, deterministic for a seed;
//! - [`pipeline`]: converter, noise filter, Hough transform and wall extraction;
//! - [`soar_loop`]: the SoarRobot loop joining simulator, pipeline and the thesis rules;
//! - [`experiment`]: `rusoar slam`, the thesis's experiment over many seeds, and [`report`]:
//!   its figures (SVG and PNG) and `report.md`, both reading [`results`] (the experiment's
//!   options and runs as data) and [`stats`] (the statistics over seeds); [`plan`]: the
//!   experiment as runs that can be carried out apart (threads, or Ray tasks from Python)
//!   and assembled into the same files;
//! - [`variant`]: the controls and ablations (`--drift`, `--variant`, the constants), and
//!   [`attribution`]: which rule made each correction, on what evidence;
//! - [`geom`], [`rng`]: plane geometry and the seeded random numbers they share;
//! - [`fixed`]: fast fixed-decimal printing for the step records and `exec` results.
//!
//! Sources: the thesis's "Hough-Transform Java" section (C. Jamroendararasame, *SoarSLAM*,
//! M.S. thesis, Pace University, 2007), ARIA's `params/p2dx.p` (Pioneer geometry) and Stage
//! 2.0.x's `model_ranger.c` and `model_position.c` (sonar and odometry models).

pub mod attribution;
pub mod compare;
pub mod ekf;
pub mod experiment;
pub mod fixed;
pub mod functions;
pub mod functions_v2;
pub mod geom;
pub mod io_log;
pub mod method;
pub mod odometry;
pub mod output_file;
pub mod pioneer;
pub mod pipeline;
pub mod plan;
pub mod report;
pub mod results;
pub mod rng;
pub mod sim;
pub mod soar_loop;
pub mod sonar;
pub mod stats;
pub mod variant;
pub mod world;

pub use geom::{Point, Pose, Segment};
pub use odometry::{Biases, DriftParams, Odometry};
pub use pioneer::{Motion, Pioneer};
pub use pipeline::{Settings as PipelineSettings, Wall};
pub use rng::{Rng, Streams};
pub use sim::{SimStep, Simulator};
pub use sonar::{NoisePreset, SonarModel, Transducer, NUM_SONARS, P2DX_SONARS};
pub use world::{RunSettings, World, WorldError};
