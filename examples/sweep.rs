//! A randomised sweep of scenes the fixtures do not contain, checked against the
//! issue's bars, clean and with Kinect v1 noise:
//! `cargo run --release --example sweep -- [workcases|hazards] [N] [SEED]`, or
//! `-- families [N] [SEED] [default|random] [FAMILY-INDEX]` for the scene families of
//! `sim::families` on the default rig or on random mounts and cameras (without an
//! index, `Family::ALL`'s in turn; index 11 is `Family::LATER`'s rock under the belly
//! beside a one-track ramp, 12 its rock on a descent), or
//! `-- natural [N] [SEED] [default|random] [FAMILY-INDEX]` for the same scenes drawn
//! another way (`families::restyled`: value-noise rough ground, stones of four other
//! shapes), or `-- bevelled [N] [SEED] [default|random] [FAMILY-INDEX]` for them
//! with every band's vertical sides sloping (`families::bevelled`: a one-track
//! ramp's side face fading over 2-15 cm), or `-- widened [N] [SEED]
//! [default|random] [FAMILY-INDEX]` for them with each band under one side wider
//! than the track (`families::widened`: its inner edge 0-15 cm into the belly band),
//! or `-- rounded [N] [SEED] [default|random] [FAMILY-INDEX]` for them with every
//! ramp's toe rounded (`families::rounded`: over 5-40 cm across the toe line), or
//! `-- hazards N SEED random` for the go/stop edges on random rigs, each edge where
//! the rig sees the tracks, or `-- edges N SEED` for impassable edges that sweep
//! does not draw (a step down under one side, a descent steeper than the limit, a
//! block in a track, ditches, a too-steep ramp met obliquely), also on random rigs,
//! where any verdict but go passes (a ditch whose floor the camera cannot see is
//! unknown ground); `-- posts N SEED`, a post 3-8 cm square and 16-50 cm high in a
//! track, on flat or rough ground or up a one-track ramp, on random rigs that see it
//! whole (its base and its top), where likewise any verdict but go passes;
//! `-- oblique N SEED`, climbable ramps up and down whose toe line runs at 20-60° to
//! the axle, on random rigs, judged go or not,
//! except where the camera meets the surface in the tracks at under `GRAZING_DEG` (a
//! descent as steep as the line of sight to it is not seen there): any verdict
//! passes, and the last lines count those frames; `families`, `natural`, `bevelled`,
//! `widened` and `rounded` excuse a scene due go in the same way, its incidence taken
//! on its planes alone (no rough ground, no stones, each band's sides drawn vertical).
//! `ONLY=3,7` checks
//! just those scenes of the sweep. The last line counts the failures and, of them,
//! the gos where a stop was due. `DUMP=DIR` writes each failing scene's terrain
//! (`N.json`, for `cells`) and configuration (`N.toml`, for `cells`' `CONFIG` and
//! `rover-terrain inspect --config`) there; with `ALL=1`, every scene's.
//! `NOISE=SCALE[,DROPOUT]` scales the noisy frames' depth σ (`KinectNoise`'s, 1 by
//! default) and sets the fraction of their pixels lost (1 % by default), as a camera
//! noisier than a Kinect v1 gives. `FLYING=FRACTION` also mixes that fraction
//! of the noisy frames' depth-edge pixels (`sim::FlyingPixels`, as time-of-flight
//! cameras give). Both apply to the `APPROACH` drives' frames too. `EXACT=1` draws each frame with the second renderer of
//! `tests/common/second_renderer.rs` (its own rays, exact planes and faces) instead of
//! `sim::render`; scenes it cannot draw (rough ground, stones, rocks on anything but
//! flat ground) are skipped, and the last line counts them. `ALL=1` also prints every
//! frame's verdict (decision, hazards, feature, tilt, how far each band is seen):
//! two builds' outputs, sorted, diff to exactly the frames whose verdict changed.
//! `WANT=1` also prints each frame's expectation on a line of its own (`want #N
//! noisy=...`), so that errors in distance and gradient can be tallied over frames
//! that pass as well as those that fail. A go where a stop was due also prints, for
//! each stone or rock drawn 12 cm or higher, how high its apex stands over the ground
//! before it (`RELIEF #N ...`, sampled from the height field); a stop where a go was
//! due prints it for every stone and rock. A failed frame on rough ground under one
//! straight full-width ramp or descent prints the plane of the rendered surface itself
//! from the drawn toe to where the tracks are seen (`SURFACE #N ...`,
//! `families::surface_toe`): rough ground's bumps move it off the drawn ramp, and no
//! fit to what the camera sees can come nearer. A go where a stop was due on a mount that
//! never sees an obstacle a wheel radius high whole in some strip of the corridor
//! (`rover_terrain::coverage`) prints `COVER #N ...` naming those strips, and a line
//! counts such frames: no frame of that mount can measure what stands there.
//!
//! Where a stone, rock, block or step up in the corridor has its top out of view
//! (`sim::sight::unseen_tops`: outside the image or its top rows, or out of range),
//! how high it stands is not seen: a verdict not go whose every hazard lies within
//! `sim::sight::TOP_REACH_M` of such an obstacle along x, on its side, passes (a go is judged as
//! usual, and a go where a stop was due fails); a line before the last counts those
//! frames, and with `ALL=1` a line `TOP #N ...` names each such obstacle.
//!
//! Where a scene drawn as climbable rises under the belly band high enough for the
//! belly to strike it (`sim::clearance::belly_strike`: a ramp under one half of the
//! corridor, its edge on the centre line, past 0.91 m high on the default rover), a
//! stop whose every hazard lies in the belly band no nearer than `TOP_REACH_M` before
//! the strike passes, and a go whose belly band is reported seen as far as where the
//! ground stands `STRIKE_MARGIN_M` (5 cm) over the underside fails as a go where a
//! stop was due; a line before the last counts the stops.
//!
//! `MAX_RANGE=M` sets every rig's far range limit (`camera.max_range_m`, 4.5 m as
//! drawn) to `M` metres after the scene is drawn: where it falls inside the corridor,
//! surfaces leave the sensor's range there. A scene's obstacle may then lie out of
//! range, so only the stops where a go was due (and a go's measures) count.
//!
//! `APPROACH=BACK_M,STEP_M,AHEAD_M` (default `1,0.1,1` when set to `1`) drives the
//! rover of each go where a stop was due straight up to and past the scene's pose:
//! from `BACK_M` behind it to `AHEAD_M` past it, `STEP_M` a frame with odometry (the
//! terrain memory fusing, as in service: `sim::drive::analyse_drive`), its frames
//! noisy where the go was (each
//! frame its own noise seed, so the drive's frame at the pose is not the sweep's
//! noisy frame, and may differ from it). A line `APPROACH #N noisy=...` says where
//! along that drive the verdict is first not go (metres from the scene's pose,
//! negative before it), with which hazard, and how many frames after it go again, then
//! every frame's verdict in turn (`.` go, `S` stop, `U` unknown), or that every frame
//! goes; the last line sums them up. A rover driving so stops at the
//! first. An obstacle the scene's frame does not see whole (the view ends on it, or
//! on its side) should be found a frame or two nearer, or was found farther back; one
//! that goes all the way is the false go to fix first. With `HOLD=N` as well, the
//! rover stops at once where the drive is first not go and holds that pose for `N`
//! frames (noisy ones each with its own noise), the memory fusing them, as a stopped
//! rover's camera goes on: a line `HOLD #N ...` says how many of those go (a go there
//! would set the rover moving again).

#[path = "../tests/common/second_renderer.rs"]
mod second;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rover_terrain::analysis::GRAZING_DEG;
use rover_terrain::coverage::Coverage;
use rover_terrain::sim::{
    self, families, random, Element, Expectation, Extent, KinectNoise, Terrain, Tolerance,
};
use rover_terrain::validate::{compare, CLEAN, NOISY};
use rover_terrain::verdict::Hazard;
use rover_terrain::{Config, Decision, Pipeline, Verdict};

/// What a sweep run draws and reports: its arguments and environment (see the module
/// doc).
struct Options {
    /// The scene mode (first argument; `workcases` when absent).
    mode: String,
    /// How many scenes (second argument; 80).
    n: usize,
    /// The draws' seed (third argument; 1).
    seed: u64,
    /// Fourth argument `random`: a random mount and camera per scene.
    random_rig: bool,
    /// Fifth argument, `families` modes: just this family (its index in
    /// `families::Family::ALL`, then `LATER`: `families::Family::by_index`).
    family: Option<usize>,
    /// ONLY=i,j,...: render just those scenes (the draws before them still happen).
    only: Option<Vec<usize>>,
    /// The noisy frames' noise: `NOISE=SCALE[,DROPOUT]` and `FLYING=FRACTION`.
    noise: Noise,
    /// EXACT=1: render with the second renderer.
    exact: bool,
    /// ALL=1 and WANT=1: what to print of every frame.
    print: Printing,
    /// DUMP=DIR: where to write the failing scenes (with `ALL=1`, every scene).
    dump: Option<std::path::PathBuf>,
    /// APPROACH=BACK_M,STEP_M,AHEAD_M (or anything else for 1,0.1,1): drive up to
    /// each false go.
    approach: Option<Drive>,
    /// HOLD=N, with APPROACH: the rover stops where the drive is first not go and
    /// holds there N frames.
    hold: Option<usize>,
    /// MAX_RANGE=M: every rig's camera sees to M metres.
    max_range: Option<f64>,
}

impl Options {
    fn parse() -> Self {
        let args: Vec<String> = std::env::args().collect();
        let env = |name: &str| std::env::var(name).ok();
        let on = |name: &str| env(name).is_some_and(|v| v == "1");
        Options {
            mode: args.get(1).map_or("workcases", String::as_str).to_string(),
            n: args.get(2).and_then(|s| s.parse().ok()).unwrap_or(80),
            seed: args.get(3).and_then(|s| s.parse().ok()).unwrap_or(1),
            random_rig: args.get(4).map(String::as_str) == Some("random"),
            family: args.get(5).and_then(|s| s.parse::<usize>().ok()),
            only: env("ONLY").map(|v| v.split(',').filter_map(|s| s.parse().ok()).collect()),
            noise: Noise::parse(env("NOISE"), env("FLYING")),
            exact: on("EXACT"),
            print: Printing {
                all: on("ALL"),
                want_too: on("WANT"),
            },
            dump: env("DUMP").map(std::path::PathBuf::from),
            approach: env("APPROACH").map(|v| {
                let p: Vec<f64> = v.split(',').filter_map(|s| s.parse().ok()).collect();
                match p[..] {
                    [back, step, ahead] if back >= 0.0 && step > 0.0 && ahead > 0.0 => {
                        Drive { back, step, ahead }
                    }
                    _ => Drive {
                        back: 1.0,
                        step: 0.1,
                        ahead: 1.0,
                    },
                }
            }),
            hold: env("HOLD").map(|v| v.parse().expect("HOLD is a count of frames")),
            max_range: env("MAX_RANGE").map(|v| {
                v.parse()
                    .ok()
                    .filter(|m: &f64| m.is_finite() && *m > 1.0)
                    .expect("MAX_RANGE is a range in metres over 1")
            }),
        }
    }
}

/// The noise of a sweep's noisy frames (and its drives' frames): Kinect v1 noise,
/// its depth σ scaled and its dropout set by `NOISE=SCALE[,DROPOUT]` (default 1 and
/// `KinectNoise`'s 1 %), then, with `FLYING=FRACTION`, that fraction of the depth-edge
/// pixels mixed.
#[derive(Debug, Clone, Copy)]
struct Noise {
    /// Factor on `KinectNoise`'s σ per squared metre of depth.
    sigma_scale: f64,
    /// Fraction of pixels lost, 0..1.
    dropout: f64,
    /// Fraction of depth-edge pixels mixed (`sim::FlyingPixels`), if any.
    flying: Option<f64>,
}

impl Noise {
    /// From `NOISE` and `FLYING`'s values; a malformed one stops the sweep.
    fn parse(noise: Option<String>, flying: Option<String>) -> Self {
        let kinect = KinectNoise::default();
        let (sigma_scale, dropout) = match noise {
            None => (1.0, kinect.dropout),
            Some(v) => {
                let p: Vec<f64> = v
                    .split(',')
                    .map(|s| s.parse().expect("NOISE is SCALE[,DROPOUT], numbers"))
                    .collect();
                match p[..] {
                    [scale] => (scale, kinect.dropout),
                    [scale, dropout] => (scale, dropout),
                    _ => panic!("NOISE is SCALE[,DROPOUT]"),
                }
            }
        };
        assert!(
            sigma_scale >= 0.0 && (0.0..1.0).contains(&dropout),
            "NOISE: SCALE at least 0, DROPOUT 0..1"
        );
        Noise {
            sigma_scale,
            dropout,
            flying: flying.map(|v| v.parse().expect("FLYING is a fraction")),
        }
    }

    /// Apply it to `frame`, from `config`'s camera, with `seed`.
    fn apply(&self, seed: u64, frame: &mut rover_terrain_drivers::DepthFrame, config: &Config) {
        let kinect = KinectNoise::default();
        KinectNoise {
            seed,
            sigma_per_m2: kinect.sigma_per_m2 * self.sigma_scale,
            dropout: self.dropout,
            ..kinect
        }
        .apply(frame, config.camera.hfov_deg);
        if let Some(fraction) = self.flying {
            sim::FlyingPixels {
                seed,
                fraction,
                ..Default::default()
            }
            .apply(frame);
        }
    }
}

/// What to print of every frame: `ALL=1` its verdict (and the obstacles whose top is
/// out of view), `WANT=1` its expectation.
#[derive(Debug, Clone, Copy)]
struct Printing {
    all: bool,
    want_too: bool,
}

impl Printing {
    /// Print frame `label`'s verdict `v`, its expectation `want` and each of `tops`
    /// (the obstacles whose top is out of view; `excused`: whether they passed `v`),
    /// as asked.
    fn frame(
        self,
        label: &str,
        v: &Verdict,
        want: &Expectation,
        (tops, excused): (&[sim::sight::UnseenTop], bool),
    ) {
        if self.all {
            println!(
                "{label} {:?} hazards={:?} feature={:?} tilt={:?} seen_to={:?}",
                v.decision, v.hazards, v.feature, v.tilt, v.seen_to_m
            );
        }
        if self.want_too {
            println!("want {label} {want:?}");
        }
        if self.all {
            for o in tops {
                println!(
                    "TOP {label} {:?}: a top at ({:.2}, {:.2}, {:.3}) m out of view{}",
                    v.decision,
                    o.top.x,
                    o.top.y,
                    o.top.z,
                    if excused { ", excused" } else { "" }
                );
            }
        }
    }
}

fn main() {
    let Options {
        mode,
        n,
        seed,
        random_rig,
        family,
        only,
        noise,
        exact,
        print,
        dump: dump_dir,
        approach,
        hold,
        max_range,
    } = Options::parse();
    let mode = mode.as_str();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut t = Tally::default();
    let mut approaches = Approaches::default();
    for i in 0..n {
        let (terrain, want, mut config, tol) = draw(&mut rng, mode, i, random_rig, family);
        if let Some(m) = max_range {
            config.camera.max_range_m = m;
        }
        if only.as_ref().is_some_and(|o| !o.contains(&i)) {
            continue;
        }
        let mut pipeline = Pipeline::new(config.clone()).expect("config works");
        let frame = if exact {
            let Some(frame) = second::frame(&terrain, &config) else {
                t.not_drawn += 1;
                continue;
            };
            frame
        } else {
            sim::render(&terrain, &config)
        };
        let unseen = unseen_at_grazing(mode, &want, &terrain, &config);
        // A stone, rock, block or step up whose top the camera cannot see: how high it stands
        // is not seen, so any verdict but go is right (a go is judged as usual).
        let unseen_tops = sim::sight::unseen_tops(&terrain, &config);
        let strike = Strike::of(&terrain, &config, &want);
        let never_whole = Coverage::for_rover(&config).never_whole_at();
        for noisy in [false, true] {
            let mut f = frame.clone();
            let noise_seed = seed * 1000 + i as u64;
            if noisy {
                noise.apply(noise_seed, &mut f, &config);
            }
            let v = pipeline.process(&f).expect("frame fits");
            if unseen {
                t.grazing.0 += 1;
                t.grazing.1 += usize::from(v.decision != Decision::Go);
            }
            let top_excused_here =
                sim::sight::not_go_for_unseen_tops(v, &unseen_tops, &config.rover);
            t.top_excused += usize::from(top_excused_here);
            let belly_excused_here = strike.excuses(v);
            t.belly_excused += usize::from(belly_excused_here);
            let over_strike = strike.go_over(v);
            let fails = if let Some(x) = over_strike {
                vec![format!(
                    "go where the belly strikes the ground {x:.2} m out"
                )]
            } else if unseen || top_excused_here || belly_excused_here {
                Vec::new()
            } else {
                judge(mode, &want, if noisy { &tol.1 } else { &tol.0 }, v)
            };
            let label = format!("#{i} noisy={noisy}");
            print.frame(&label, v, &want, (&unseen_tops, top_excused_here));
            t.total += 1;
            if v.decision == Decision::Go && (want.verdict != Decision::Go || over_strike.is_some())
            {
                t.false_go += 1;
                if !never_whole.is_empty() {
                    t.uncovered_false_go += 1;
                    println!(
                        "COVER {label}: the mount never sees an obstacle a wheel radius high whole at y = {never_whole} m"
                    );
                }
                if let Some(drive) = approach {
                    let noise = noisy.then_some((noise, noise_seed));
                    approaches.drive_up(drive, hold, (&terrain, &config, noise), &label);
                }
            }
            if let (Some(dir), true) = (&dump_dir, print.all || !fails.is_empty()) {
                dump(dir, i, &terrain, &config);
            }
            if !fails.is_empty() {
                t.failures += 1;
                println!(
                    "FAIL #{i} noisy={noisy} {:?} mount={:?} cam={}x{}: {fails:?} hazards={:?} feature={:?}",
                    terrain.elements, config.mount, config.camera.width, config.camera.height, v.hazards, v.feature
                );
                for r in triage_reliefs(&terrain, v.decision, want.verdict) {
                    println!("RELIEF #{i} noisy={noisy} {r}");
                }
                if let Some(s) = surface_plane(&terrain, &config, v) {
                    println!("SURFACE #{i} noisy={noisy} {s}");
                }
            }
        }
    }
    t.report(mode, exact, approach.map(|d| (d, &approaches)));
}

/// What a sweep counts over its frames.
#[derive(Debug, Default)]
struct Tally {
    /// Frames analysed.
    total: usize,
    /// Frames that failed their expectation.
    failures: usize,
    /// Frames that went where a stop was due.
    false_go: usize,
    /// Of those, frames on a mount that never sees part of the corridor whole.
    uncovered_false_go: usize,
    /// Frames that met a surface under [`GRAZING_DEG`], and of them those not go.
    grazing: (usize, usize),
    /// Frames not go for an obstacle whose top is out of view.
    top_excused: usize,
    /// Frames not go where the belly strikes ground drawn as climbable.
    belly_excused: usize,
    /// Scenes the second renderer could not draw (`EXACT=1`).
    not_drawn: usize,
}

impl Tally {
    /// Prints the summary: the counts, with `EXACT=1` the scenes not drawn, with
    /// `APPROACH` the drives' report, then what was excused.
    fn report(&self, mode: &str, exact: bool, approach: Option<(Drive, &Approaches)>) {
        println!(
            "{} passed, {} failed, {} false go",
            self.total - self.failures,
            self.failures,
            self.false_go
        );
        if exact {
            println!(
                "{} scenes not drawn (not made of planes and rocks)",
                self.not_drawn
            );
        }
        if let Some((drive, approaches)) = approach {
            approaches.report(drive);
        }
        println!(
            "{} frames not go for a stone, rock, block or step whose top is out of view (passed)",
            self.top_excused
        );
        println!(
            "{} false go frames on a mount that never sees part of the corridor whole (COVER)",
            self.uncovered_false_go
        );
        println!(
            "{} frames not go where the belly strikes ground drawn as climbable (passed)",
            self.belly_excused
        );
        if mode == "oblique" || FAMILY_MODES.contains(&mode) {
            println!(
                "{} frames met a surface under {GRAZING_DEG}° (any verdict passes), {} of them not go",
                self.grazing.0, self.grazing.1
            );
        }
    }
}

/// Where the belly strikes a scene drawn as climbable (`sim::clearance`: a ramp under
/// one half of the corridor, its edge on the centre line, standing high enough over
/// the other track's ground): a stop in the belly band there is right, and a go that
/// claims that ground seen is wrong. Both `None` for a scene not due go.
struct Strike {
    /// The first row the ground stands over the underside, metres.
    at: Option<f64>,
    /// The first row it stands `STRIKE_MARGIN_M` over it, metres.
    struck: Option<f64>,
}

impl Strike {
    /// The strike of `terrain` on `config`'s rover, for a scene expected `want`.
    fn of(terrain: &Terrain, config: &Config, want: &Expectation) -> Self {
        let strike = |margin_m| {
            (want.verdict == Decision::Go)
                .then(|| sim::clearance::belly_strike(terrain, config, margin_m))
                .flatten()
        };
        Strike {
            at: strike(0.0),
            struck: strike(sim::clearance::STRIKE_MARGIN_M),
        }
    }

    /// Whether `v` is a stop the strike explains.
    fn excuses(&self, v: &Verdict) -> bool {
        self.at
            .is_some_and(|x| sim::clearance::not_go_for_belly_strike(v, x))
    }

    /// Where the strike lies when `v` is a go that claims its ground seen.
    fn go_over(&self, v: &Verdict) -> Option<f64> {
        self.struck
            .filter(|&x| sim::clearance::go_over_a_strike(v, x))
    }
}

/// How verdict `v` of a frame of `mode` misses `want` within `tol`: in `edges` and
/// `posts`, stop or unknown both pass (a ditch whose floor lies in its own shadow is
/// unknown ground: how deep it is, is not seen), and only a go fails.
fn judge(mode: &str, want: &Expectation, tol: &Tolerance, v: &Verdict) -> Vec<String> {
    if !matches!(mode, "edges" | "posts") {
        compare(want, tol, v)
    } else if v.decision == Decision::Go {
        vec![format!("go where {:?} was due", want.verdict)]
    } else {
        Vec::new()
    }
}

/// The modes that draw `sim::families`' scenes: as drawn, restyled, with sloping
/// band sides, with bands wider than the track, with rounded toes.
const FAMILY_MODES: [&str; 5] = ["families", "natural", "bevelled", "widened", "rounded"];

/// Whether scene `terrain` of `mode`, expected `want` on `config`'s rig, is excused: a
/// climbable surface the camera meets at grazing incidence somewhere in the tracks (a
/// descent as steep as the line of sight to it) is not seen there, so any verdict
/// passes, and go is the analysis' inference. In `families`, `natural` and
/// `bevelled` (and `widened`), for a scene due go, judged on its planes alone (the far flanks of rough
/// ground's bumps and of stones face away from the camera too, and excuse nothing).
fn unseen_at_grazing(mode: &str, want: &Expectation, terrain: &Terrain, config: &Config) -> bool {
    match mode {
        "oblique" => grazing(terrain, config),
        m if FAMILY_MODES.contains(&m) && want.verdict == Decision::Go => {
            grazing(&planes_of(terrain), config)
        }
        _ => false,
    }
}

/// [`reliefs`] for a failed frame that decided `got` where `want` was due: for a false
/// go the stones that should have stopped it (12 cm or higher); for a false stop
/// every stone, any of which may stand over a wheel radius above the dip before it;
/// otherwise none.
fn triage_reliefs(terrain: &Terrain, got: Decision, want: Decision) -> Vec<String> {
    match (got, want) {
        (Decision::Go, w) if w != Decision::Go => reliefs(terrain, 0.12),
        (Decision::Stop, Decision::Go) => reliefs(terrain, 0.0),
        _ => Vec::new(),
    }
}

/// For a false go's or a false stop's triage: each stone and rock of `terrain` drawn
/// `least_m` high or higher (metres), with how high its apex stands over the ground
/// the wheel comes from, sampled from the height field (a hand calculation, not the
/// analysis): its apex, and the mean over the 0.3 m before its foot along x. Rough
/// ground dips under some stones, and a stone drawn 15 cm high then stands a wheel
/// radius or little more over that ground; one drawn 9 cm high on a bump past a dip
/// may stand more.
fn reliefs(terrain: &Terrain, least_m: f64) -> Vec<String> {
    terrain
        .elements
        .iter()
        .filter_map(|e| match *e {
            Element::Stone {
                x_m,
                y_m,
                radius_m,
                height_m,
                ..
            }
            | Element::Rock {
                x_m,
                y_m,
                radius_m,
                height_m,
            } if height_m >= least_m => {
                let apex = terrain.height(x_m, y_m);
                let before = (0..7)
                    .map(|k| terrain.height(x_m - radius_m - 0.05 * f64::from(k), y_m))
                    .sum::<f64>()
                    / 7.0;
                Some(format!(
                    "drawn {height_m:.3} m at ({x_m:.2}, {y_m:.2}): apex {apex:.3} m, {:.3} m over the ground before it",
                    apex - before
                ))
            }
            _ => None,
        })
        .collect()
}

/// For a failed frame's triage on rough or lumpy ground under one straight full-width
/// ramp or descent: the plane of the rendered surface itself from the drawn toe to
/// where the verdict saw both tracks (`families::surface_toe`, a hand calculation).
/// Rough ground's bumps move that plane off the drawn ramp, and no fit to what the
/// camera sees comes nearer the drawn ramp than the surface it sees.
fn surface_plane(terrain: &Terrain, config: &Config, v: &Verdict) -> Option<String> {
    let rough = terrain
        .elements
        .iter()
        .any(|e| matches!(e, Element::Rough { .. } | Element::Lumpy { .. }));
    let mut ramps = terrain.elements.iter().filter_map(|e| match *e {
        Element::Ramp {
            toe_x_m,
            alpha_deg: 0.0,
            extent: Extent::Full,
            cap_m: None,
            ..
        } => Some(toe_x_m),
        _ => None,
    });
    let (Some(toe_x_m), None, true) = (ramps.next(), ramps.next(), rough) else {
        return None;
    };
    let far = f64::from(v.seen_to_m.left.min(v.seen_to_m.right));
    let (toe, gradient) = families::surface_toe(terrain, config, toe_x_m.max(0.0), far)?;
    Some(format!(
        "the rendered surface's own plane from the drawn toe to {far:.2} m: toe {toe:.3} m, gradient {gradient:.2}°"
    ))
}

/// Write scene `i`'s terrain (`i.json`, for `cells`) and configuration (`i.toml`)
/// into `dir`.
fn dump(dir: &std::path::Path, i: usize, terrain: &Terrain, config: &Config) {
    std::fs::create_dir_all(dir).expect("DUMP is a writable directory");
    let json = serde_json::to_string(&terrain.elements).expect("terrain serialises");
    std::fs::write(dir.join(format!("{i}.json")), json).expect("DUMP writable");
    let toml = toml::to_string(&config).expect("configuration serialises");
    std::fs::write(dir.join(format!("{i}.toml")), toml).expect("DUMP writable");
}

/// Whether the camera meets `terrain`'s surface under the tracks somewhere at under
/// [`GRAZING_DEG`] ([`families::least_incidence_deg`], a hand calculation).
fn grazing(terrain: &Terrain, config: &Config) -> bool {
    families::least_incidence_deg(terrain, config) < f64::from(GRAZING_DEG)
}

/// `terrain`'s planar elements alone (ramps, steps, blocks, drop-offs): without its
/// rough ground and its stones, and with each band's sloping sides drawn vertical
/// again (`Extent::Bevelled` as the `Extent::Band` it was drawn from). A bevel's
/// outer side falls away from the camera as steeply as a wall and lies 1-7 cm inside
/// the track: judged on it, every bevelled one-track ramp and every pair of ramps
/// was excused (`bevelled 100 901 default 9`: 200 of 200 frames), and their false
/// stops went uncounted. The ground the tracks drive on is the band's own.
fn planes_of(terrain: &Terrain) -> Terrain {
    Terrain::new(
        terrain
            .elements
            .iter()
            .filter(|e| {
                !matches!(
                    e,
                    Element::Rough { .. }
                        | Element::Lumpy { .. }
                        | Element::Rock { .. }
                        | Element::Stone { .. }
                )
            })
            .cloned()
            .map(|mut e| {
                if let Element::Ramp { extent, .. } | Element::Step { extent, .. } = &mut e {
                    *extent = extent.sharp();
                }
                e
            })
            .collect(),
    )
}

/// Scene `i` of `mode`: its terrain, expectation, configuration and tolerances
/// (clean, noisy).
fn draw(
    rng: &mut ChaCha8Rng,
    mode: &str,
    i: usize,
    random_rig: bool,
    family: Option<usize>,
) -> (Terrain, Expectation, Config, (Tolerance, Tolerance)) {
    let tol = (CLEAN, NOISY);
    match mode {
        // Posts narrower than a cell or two in a track, on a random rig that sees one
        // whole (a rig that sees none is drawn again).
        "posts" => (0..100)
            .find_map(|_| {
                let rig = families::Rig::random(rng);
                let at = families::judged_span(&rig.config);
                random::post_scene_within(rng, &rig.config, at)
                    .map(|(t, w)| (t, w, rig.config, tol))
            })
            .expect("one of 100 random rigs sees a post whole"),
        // On random rigs (`edges` and `oblique` always, `hazards` when asked), each
        // scene where its rig sees both tracks.
        "edges" | "oblique" | "hazards" if random_rig || mode != "hazards" => {
            let rig = families::Rig::random(rng);
            let at = families::judged_span(&rig.config);
            let (t, w) = match mode {
                "hazards" => random::hazard_scene_within(rng, i, at),
                // Impassable edges the hazard sweep does not draw.
                "edges" => random::edge_scene_within(rng, i, at),
                // Climbable ramps up and down met obliquely.
                _ => random::oblique_scene_within(rng, at),
            };
            (t, w, rig.config, tol)
        }
        "hazards" => {
            let (t, w) = random::hazard_scene(rng, i);
            (t, w, Config::default(), tol)
        }
        m if FAMILY_MODES.contains(&m) => {
            let rig = if random_rig {
                families::Rig::random(rng)
            } else {
                families::Rig::default_rig()
            };
            let fam = match family {
                Some(k) => families::Family::by_index(k).expect("a family index"),
                None => families::Family::ALL[i % families::Family::ALL.len()],
            };
            let mut d = families::draw(rng, fam, rig);
            type Restyle = fn(&mut ChaCha8Rng, families::Draw) -> families::Draw;
            let restyle: Option<(u64, Restyle)> = match mode {
                "natural" => Some((1, families::restyled)),
                "bevelled" => Some((2, families::bevelled)),
                "widened" => Some((3, families::widened)),
                "rounded" => Some((4, families::rounded)),
                _ => None,
            };
            if let Some((stream, restyle)) = restyle {
                // Its own stream, so the scenes are `families`' scenes, drawn anew.
                let mut style = rng.clone();
                style.set_stream(stream);
                d = restyle(&mut style, d);
            }
            (d.terrain, d.expect, d.rig.config, d.tolerance)
        }
        _ => {
            let (t, w) = random::workcase_scene(rng, i);
            (t, w, Config::default(), tol)
        }
    }
}

/// A drive up to a scene's pose: from `back` metres behind it to `ahead` past it,
/// `step` metres a frame.
#[derive(Debug, Clone, Copy)]
struct Drive {
    back: f64,
    step: f64,
    ahead: f64,
}

impl Drive {
    /// Drive it in `terrain` on `config`'s rig, each frame rendered with odometry
    /// and, with `noise`'s seed, Kinect noise (seeded per frame), through one
    /// pipeline (its terrain memory fusing them).
    fn run(self, terrain: &Terrain, config: &Config, noise: Option<(Noise, u64)>) -> Approach {
        let n = ((self.back + self.ahead) / self.step).round() as usize;
        let step = sim::drive::Step {
            forward_m: self.step,
            turn_rad: 0.0,
        };
        Approach {
            drive: self,
            frames: self.frames(terrain, config, noise, &vec![step; n]),
        }
    }

    /// A rover that stops where the drive is first not go (frame `first`), at once:
    /// it holds that pose for `hold` frames (each with its own noise, when noisy),
    /// the memory fusing them. Returns how many of those go.
    fn hold(
        self,
        terrain: &Terrain,
        config: &Config,
        noise: Option<(Noise, u64)>,
        (first, hold): (usize, usize),
    ) -> usize {
        let moving = sim::drive::Step {
            forward_m: self.step,
            turn_rad: 0.0,
        };
        let still = sim::drive::Step {
            forward_m: 0.0,
            turn_rad: 0.0,
        };
        let mut steps = vec![moving; first];
        steps.extend(std::iter::repeat_n(still, hold));
        let frames = self.frames(terrain, config, noise, &steps);
        frames[first + 1..]
            .iter()
            .filter(|(_, f)| f.is_none())
            .count()
    }

    /// Each frame of a drive of `steps` from `back` behind the scene's pose: its x
    /// (metres from the scene's pose) and `None` for a go, else its decision and
    /// nearest hazard.
    fn frames(
        self,
        terrain: &Terrain,
        config: &Config,
        noise: Option<(Noise, u64)>,
        steps: &[sim::drive::Step],
    ) -> Vec<(f64, Option<NotGo>)> {
        let start = sim::Pose {
            x: -self.back,
            ..sim::Pose::default()
        };
        let mut drive = sim::drive::render_drive_from(terrain, config, start, steps, 1.0, 10.0);
        if let Some((noise, seed)) = noise {
            for (k, (frame, _, _)) in drive.iter_mut().enumerate() {
                noise.apply(
                    seed.wrapping_mul(1000).wrapping_add(k as u64),
                    frame,
                    config,
                );
            }
        }
        // Each frame's recorded odometry moves the terrain memory, as in service.
        let verdicts = sim::drive::analyse_drive(&drive, config).expect("frames fit");
        drive
            .iter()
            .zip(&verdicts)
            .map(|((_, pose, _), v)| {
                let nearest = v
                    .hazards
                    .iter()
                    .copied()
                    .min_by(|a, b| a.distance_m.total_cmp(&b.distance_m));
                // Metres from the scene's pose, on the step's grid (no −0.00).
                let x = (pose.x / self.step).round() * self.step + 0.0;
                (
                    x,
                    (v.decision != Decision::Go).then_some((v.decision, nearest)),
                )
            })
            .collect()
    }
}

/// What a [`Drive`] showed: per frame, its pose's x (metres from the scene's pose)
/// and `None` for a go, else its decision and nearest hazard.
struct Approach {
    drive: Drive,
    frames: Vec<(f64, Option<NotGo>)>,
}

/// A frame that did not go: its decision and nearest hazard.
type NotGo = (Decision, Option<Hazard>);

impl Approach {
    /// The first frame that is not go.
    fn first_not_go(&self) -> Option<usize> {
        self.frames.iter().position(|(_, f)| f.is_some())
    }

    /// Go frames after the first that was not.
    fn go_again(&self) -> usize {
        self.first_not_go().map_or(0, |k| {
            self.frames[k..].iter().filter(|(_, f)| f.is_none()).count()
        })
    }

    fn describe(&self) -> String {
        let d = self.drive;
        match self.first_not_go() {
            None => format!(
                "go in every frame from {:.2} m before the scene's pose to {:.2} m past it",
                d.back, d.ahead
            ),
            Some(k) => {
                let (x, f) = self.frames[k];
                let (decision, hazard) = f.expect("not go");
                let hazard = hazard.map_or("no hazard".to_string(), |h| {
                    format!("{:?} {:?} {:.2} m", h.kind, h.side, h.distance_m)
                });
                // Each frame's verdict in turn: `.` go, `S` stop, `U` unknown.
                let frames: String = self
                    .frames
                    .iter()
                    .map(|(_, f)| match f {
                        None => '.',
                        Some((Decision::Stop, _)) => 'S',
                        Some(_) => 'U',
                    })
                    .collect();
                format!(
                    "first not go at {x:+.2} m from the scene's pose ({decision:?}, {hazard}), {} go frames after it: {frames}",
                    self.go_again()
                )
            }
        }
    }
}

/// The tally of a sweep's approaches.
#[derive(Default)]
struct Approaches {
    driven: usize,
    before: usize,
    latest_m: Option<f64>,
    never: usize,
    flickers: usize,
    /// Drives held at their first stop (`HOLD`), and how many of them went again.
    held: usize,
    held_go: usize,
}

impl Approaches {
    /// Drive up to a go where a stop was due (`terrain` on `config`'s rig, noisy with
    /// `noise`'s seed), print its `APPROACH` line and, with `hold` frames, its `HOLD`
    /// line (each after `label`), and count it.
    fn drive_up(
        &mut self,
        drive: Drive,
        hold: Option<usize>,
        (terrain, config, noise): (&Terrain, &Config, Option<(Noise, u64)>),
        label: &str,
    ) {
        let a = drive.run(terrain, config, noise);
        println!("APPROACH {label} {}", a.describe());
        self.add(&a);
        if let (Some(first), Some(n)) = (a.first_not_go(), hold) {
            let gos = drive.hold(terrain, config, noise, (first, n));
            println!(
                "HOLD {label} stopped at {:+.2} m: {gos} of {n} frames held there go",
                a.frames[first].0
            );
            self.held += 1;
            self.held_go += usize::from(gos > 0);
        }
    }

    fn add(&mut self, a: &Approach) {
        self.driven += 1;
        match a.first_not_go().map(|k| a.frames[k].0) {
            None => self.never += 1,
            Some(x) if x < 0.0 => self.before += 1,
            Some(x) => self.latest_m = Some(self.latest_m.map_or(x, |l: f64| l.max(x))),
        }
        self.flickers += usize::from(a.go_again() > 0);
    }

    fn report(&self, d: Drive) {
        let latest = self.latest_m.map_or("none".to_string(), |x| {
            format!("the latest {x:.2} m past it")
        });
        println!(
            "{} false go frames driven up to ({:.2} m back to {:.2} m on): {} not go before the \
             scene's pose, {} at or past it ({latest}), {} go all the way; {} go again after a \
             frame that was not",
            self.driven,
            d.back,
            d.ahead,
            self.before,
            self.driven - self.before - self.never,
            self.never,
            self.flickers
        );
        if self.held > 0 {
            println!(
                "{} drives held at their first stop: {} of them go again there",
                self.held, self.held_go
            );
        }
    }
}
