//! The viewer thread: what the analysis saw, for people (`run --mcap FILE`, and
//! `run --foxglove ADDR` live with the feature `foxglove-live`), off the hot path.
//!
//! The analysis stage copies each analysed frame (depth image, voxels, cells, verdict)
//! into a snapshot from a pool allocated at start, and hands it over newest-wins: when
//! the viewer is behind, the snapshot waiting for it is dropped (and counted), never a
//! verdict. Building and writing the messages (which allocates) happens on this thread
//! only.

use std::path::Path;
use std::sync::Arc;
use std::thread;

use crossbeam_channel::{bounded, Receiver, Sender, TrySendError};
use rover_terrain_drivers::DepthFrame;

use super::{bump, Counters};
use crate::foxglove::{Frames, McapOut};
use crate::grid::{Cell, GridSpec, Voxel};
use crate::inspect::Scene;
use crate::{Config, Error, Pipeline, Verdict};

/// Snapshots in the pool: one the viewer writes, one waiting, one being filled.
const POOL: usize = 3;

/// One analysed frame, copied out of the pipeline.
struct Snapshot {
    frame: DepthFrame,
    voxels: Vec<Voxel>,
    cells: Vec<Cell>,
    expected: Vec<bool>,
    verdict: Verdict,
}

impl Snapshot {
    fn with_capacity(config: &Config, spec: &GridSpec) -> Self {
        let (w, h) = (config.camera.width as usize, config.camera.height as usize);
        Snapshot {
            frame: DepthFrame::with_capacity(w, h),
            voxels: Vec::with_capacity(spec.voxel_count().min(w * h)),
            cells: Vec::with_capacity(spec.cell_count()),
            expected: Vec::with_capacity(spec.cell_count()),
            verdict: Verdict::default(),
        }
    }

    /// Copy the frame `pipeline` last analysed (within the capacities: no allocation).
    fn fill(&mut self, frame: &DepthFrame, pipeline: &Pipeline) {
        self.frame
            .reshape(frame.width(), frame.height())
            .copy_from_slice(frame.pixels());
        self.frame.seq = frame.seq;
        self.frame.timestamp_s = frame.timestamp_s;
        self.voxels.clear();
        self.voxels.extend_from_slice(pipeline.grid().voxels());
        self.cells.clear();
        self.cells.extend_from_slice(pipeline.analysed_cells());
        self.expected.clear();
        self.expected
            .extend_from_slice(pipeline.analyzer().expected());
        self.verdict.clone_from(pipeline.verdict());
    }
}

/// The analysis stage's end of the viewer.
pub(super) struct Viewer {
    ready_tx: Sender<Snapshot>,
    ready_rx: Receiver<Snapshot>,
    free_tx: Sender<Snapshot>,
    free_rx: Receiver<Snapshot>,
    counters: Arc<Counters>,
    handle: thread::JoinHandle<Result<u64, Error>>,
}

impl Viewer {
    /// Start the viewer thread writing into the MCAP file `path` and/or serving live
    /// on `live` (`HOST:PORT`).
    pub fn start(
        path: Option<&Path>,
        live: Option<&str>,
        pipeline: &Pipeline,
        counters: &Arc<Counters>,
    ) -> Result<Self, Error> {
        let config = pipeline.config().clone();
        let spec = *pipeline.grid().spec();
        let mut out = path
            .map(|p| McapOut::create(p, Frames::of(&config)))
            .transpose()?;
        #[cfg(feature = "foxglove-live")]
        let live = match live {
            Some(addr) => {
                let l = crate::foxglove::live::Live::start(addr, Frames::of(&config))?;
                log::info!(
                    "foxglove: serving the analysis live on ws://{}:{}",
                    addr.rsplit_once(':').map_or(addr, |(h, _)| h),
                    l.port()
                );
                Some(l)
            }
            None => None,
        };
        #[cfg(not(feature = "foxglove-live"))]
        if let Some(addr) = live {
            return Err(Error::Setup(format!(
                "--foxglove {addr}: built without the live viewer: rebuild with `--features foxglove-live`"
            )));
        }
        let (ready_tx, ready_rx) = bounded::<Snapshot>(1);
        let (free_tx, free_rx) = bounded::<Snapshot>(POOL);
        for _ in 0..POOL {
            let _ = free_tx.send(Snapshot::with_capacity(&config, &spec));
        }
        let (rx, back) = (ready_rx.clone(), free_tx.clone());
        let handle = thread::Builder::new()
            .name("viewer".into())
            .spawn(move || {
                // Until the analysis stage hangs up: write each snapshot, give it back.
                let mut written = 0u64;
                for s in rx {
                    let scene = Scene {
                        config: &config,
                        spec: &spec,
                        cells: &s.cells,
                        voxels: &s.voxels,
                        expected: &s.expected,
                        verdict: &s.verdict,
                        memory: None,
                    };
                    let json = s.verdict.to_json();
                    if let Some(out) = out.as_mut() {
                        out.write(&s.frame, &scene, &json)?;
                    }
                    #[cfg(feature = "foxglove-live")]
                    if let Some(l) = &live {
                        l.publish(&s.frame, &scene, &json)?;
                    }
                    written += 1;
                    let _ = back.send(s);
                }
                #[cfg(feature = "foxglove-live")]
                if let Some(l) = live {
                    l.stop();
                }
                if let Some(out) = out {
                    out.finish()?;
                }
                Ok(written)
            })
            .map_err(|e| Error::Setup(format!("cannot start the viewer thread: {e}")))?;
        Ok(Viewer {
            ready_tx,
            ready_rx,
            free_tx,
            free_rx,
            counters: Arc::clone(counters),
            handle,
        })
    }

    /// Hand the frame `pipeline` just analysed to the viewer, newest wins: with no
    /// free snapshot, or one still waiting, the oldest picture is dropped (counted in
    /// `viewer_dropped`). Never blocks, never allocates.
    pub fn offer(&self, frame: &DepthFrame, pipeline: &Pipeline) {
        let mut s = match self.free_rx.try_recv() {
            Ok(s) => s,
            // All snapshots taken: the viewer writes one and one waits; replace it.
            Err(_) => match self.ready_rx.try_recv() {
                Ok(old) => {
                    bump(&self.counters.viewer_dropped);
                    old
                }
                // The viewer just took it: this picture is the one lost.
                Err(_) => {
                    bump(&self.counters.viewer_dropped);
                    return;
                }
            },
        };
        s.fill(frame, pipeline);
        if let Err(TrySendError::Full(s) | TrySendError::Disconnected(s)) =
            self.ready_tx.try_send(s)
        {
            // One is waiting already: the newer replaces it.
            if let Ok(old) = self.ready_rx.try_recv() {
                bump(&self.counters.viewer_dropped);
                let _ = self.free_tx.try_send(old);
            }
            if self.ready_tx.try_send(s).is_err() {
                bump(&self.counters.viewer_dropped);
            }
        }
    }

    /// Let the viewer write what it holds, finish the file (stop serving), and say
    /// how many frames it wrote.
    pub fn finish(self) -> Result<u64, Error> {
        let Viewer {
            ready_tx, handle, ..
        } = self;
        drop(ready_tx);
        handle
            .join()
            .map_err(|_| Error::Setup("the viewer thread panicked".into()))?
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offers_faster_than_the_viewer_writes_are_written_or_counted_dropped() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("v.mcap");
        let mut pipeline = Pipeline::new(Config::default()).unwrap();
        let frame = crate::sim::render(&crate::sim::Terrain::flat(), &Config::default());
        pipeline.process(&frame).unwrap();
        let counters = Arc::new(Counters::default());
        let viewer = Viewer::start(Some(&path), None, &pipeline, &counters).unwrap();
        const OFFERED: u64 = 60;
        for _ in 0..OFFERED {
            viewer.offer(&frame, &pipeline);
        }
        let written = viewer.finish().unwrap();
        let dropped = super::super::get(&counters.viewer_dropped);
        assert!(written >= 1, "the viewer wrote nothing");
        assert_eq!(
            written + dropped,
            OFFERED,
            "{written} written, {dropped} dropped"
        );
        let bytes = std::fs::read(&path).unwrap();
        let stats = mcap::Summary::read(&bytes).unwrap().unwrap().stats.unwrap();
        assert!(stats.channel_message_counts.values().all(|&n| n == written));
    }
}
