//! The analysis live over the Foxglove WebSocket protocol (`run --foxglove [ADDR]`,
//! feature `foxglove-live`): the same channels as the MCAP output ([`super::channels`]),
//! served by the `foxglove` crate's WebSocket server on its own runtime threads.
//!
//! Only the viewer thread publishes here, never the analysis. Toward each connected
//! viewer the server keeps a bounded backlog and drops the oldest messages when a
//! viewer is slow (the crate's behaviour); a viewer that connects, stalls or leaves
//! changes nothing for the verdicts.

use std::sync::Arc;

use foxglove::{ChannelBuilder, Context, PartialMetadata, RawChannel, Schema, WebSocketServer};
use rover_terrain_drivers::DepthFrame;

use super::{channels, payloads, Frames, CHANNELS};
use crate::inspect::Scene;
use crate::Error;

/// Messages kept per viewer before the oldest are dropped (about 4 frames).
pub const BACKLOG: usize = 4 * CHANNELS;

/// A running live server and its channels.
pub struct Live {
    /// The channels' context: they are advertised only while it lives.
    _context: Arc<Context>,
    server: foxglove::WebSocketServerHandle,
    channels: Vec<Arc<RawChannel>>,
    frames: Frames,
}

impl std::fmt::Debug for Live {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Live(port {})", self.server.port())
    }
}

impl Live {
    /// Serve on `addr` (`HOST:PORT`; port 0 picks a free one), messages in the TF
    /// frames `frames`.
    pub fn start(addr: &str, frames: Frames) -> Result<Self, Error> {
        let bad = |why: String| Error::Setup(format!("--foxglove {addr}: {why}"));
        let (host, port) = addr
            .rsplit_once(':')
            .ok_or_else(|| bad("expected HOST:PORT".into()))?;
        let port: u16 = port
            .parse()
            .map_err(|_| bad(format!("{port:?} is not a port number")))?;
        let ctx = Context::new();
        let mut live = Vec::with_capacity(CHANNELS);
        for c in channels()? {
            let schema = Schema::new(c.schema_name, c.schema_encoding, c.schema);
            let channel = ChannelBuilder::new(c.topic)
                .context(&ctx)
                .schema(schema)
                .message_encoding(c.message_encoding)
                .build_raw()
                .map_err(|e| bad(format!("channel {}: {e}", c.topic)))?;
            live.push(channel);
        }
        let server = WebSocketServer::new()
            .name("rover-terrain")
            .bind(host, port)
            .context(&ctx)
            .message_backlog_size(BACKLOG)
            .start_blocking()
            .map_err(|e| bad(e.to_string()))?;
        Ok(Live {
            _context: ctx,
            server,
            channels: live,
            frames,
        })
    }

    /// The port served on.
    pub fn port(&self) -> u16 {
        self.server.port()
    }

    /// Viewers connected now.
    pub fn viewers(&self) -> usize {
        self.server.client_count()
    }

    /// Publish one analysed frame to every subscribed viewer.
    pub fn publish(
        &self,
        frame: &DepthFrame,
        scene: &Scene<'_>,
        verdict: &serde_json::Value,
    ) -> Result<(), Error> {
        let ns = rover_terrain_drivers::ros2::writer::nanos(frame.timestamp_s);
        let out = payloads(frame, scene, verdict, &self.frames)?;
        for (channel, data) in self.channels.iter().zip(out) {
            channel.log_with_meta(&data, PartialMetadata { log_time: Some(ns) });
        }
        Ok(())
    }

    /// Stop serving (viewers are disconnected).
    pub fn stop(self) {
        let _ = self.server.stop();
    }
}
