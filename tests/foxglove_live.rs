//! `run --foxglove ADDR` (feature `foxglove-live`): a WebSocket client speaking the
//! Foxglove protocol connects to the running service, subscribes to the verdict and
//! the point cloud, receives them, and leaves mid-stream without closing; the
//! service goes on sending every verdict, and its camera, analysis and link threads
//! allocate nothing while the viewer is connected and after it left.
#![cfg(feature = "foxglove-live")]

use std::collections::BTreeMap;
use std::io::Read;
use std::sync::atomic::Ordering;
use std::time::Duration;

use foxglove::messages::PointCloud;
use foxglove::Decode;
use rover_terrain::foxglove::{TOPIC_CLOUD, TOPIC_VERDICT};
use rover_terrain::link::proto::serial::{Decoder, Message};
use rover_terrain::link::LinkTarget;
use rover_terrain::service::{self, Notifier, Options, StopReason};
use rover_terrain::Config;
use rover_terrain_drivers::{CameraSpec, Faults};
use serialport::{SerialPort, TTYPort};
use tungstenite::client::IntoClientRequest;

#[path = "common/counting.rs"]
mod counting;
use counting::{Counting, ALLOCATIONS, COUNTING};

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Verdicts before the viewer connects, and watched while it is there and after.
const WARM_UP: usize = 10;
const WATCHED: usize = 60;

fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
}

/// Connect, subscribe to the verdict and cloud, take `want` verdicts and a cloud,
/// then drop the connection without a close handshake.
fn viewer(port: u16, want: usize) -> (Vec<serde_json::Value>, Vec<PointCloud>) {
    let mut req = format!("ws://127.0.0.1:{port}")
        .into_client_request()
        .unwrap();
    req.headers_mut()
        .insert("Sec-WebSocket-Protocol", "foxglove.sdk.v1".parse().unwrap());
    let (mut ws, response) = tungstenite::connect(req).unwrap();
    // A server that stops talking fails the test instead of hanging it.
    if let tungstenite::stream::MaybeTlsStream::Plain(s) = ws.get_ref() {
        s.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
    }
    assert_eq!(
        response.headers()["Sec-WebSocket-Protocol"],
        "foxglove.sdk.v1"
    );
    let mut topics: BTreeMap<String, u64> = BTreeMap::new();
    while !(topics.contains_key(TOPIC_VERDICT) && topics.contains_key(TOPIC_CLOUD)) {
        if let tungstenite::Message::Text(t) = ws.read().unwrap() {
            let v: serde_json::Value = serde_json::from_str(&t).unwrap();
            if v["op"] == "advertise" {
                for c in v["channels"].as_array().unwrap() {
                    topics.insert(
                        c["topic"].as_str().unwrap().into(),
                        c["id"].as_u64().unwrap(),
                    );
                }
            }
        }
    }
    let subscribe = serde_json::json!({"op": "subscribe", "subscriptions": [
        {"id": 1, "channelId": topics[TOPIC_VERDICT]},
        {"id": 2, "channelId": topics[TOPIC_CLOUD]},
    ]});
    ws.send(tungstenite::Message::Text(subscribe.to_string().into()))
        .unwrap();
    let (mut verdicts, mut clouds) = (Vec::new(), Vec::new());
    while verdicts.len() < want || clouds.is_empty() {
        let tungstenite::Message::Binary(b) = ws.read().unwrap() else {
            continue;
        };
        // Message data: opcode 1, subscription id (u32 LE), log time (u64 LE), payload.
        assert_eq!(b[0], 1, "a message data frame");
        let sub = u32::from_le_bytes(b[1..5].try_into().unwrap());
        let payload = &b[13..];
        match sub {
            1 => verdicts.push(serde_json::from_slice(payload).unwrap()),
            2 => clouds.push(PointCloud::decode(payload).unwrap()),
            other => panic!("subscription {other} was never asked for"),
        }
    }
    // Leave mid-stream: drop the socket, no close frame.
    drop(ws);
    (verdicts, clouds)
}

#[test]
fn a_viewer_subscribes_receives_and_leaves_while_verdicts_flow_without_allocating() {
    let (mut master, slave) = TTYPort::pair().unwrap();
    master.set_timeout(Duration::from_millis(100)).unwrap();
    let mut config = Config::default();
    config.service.stats_interval_s = 3600;
    config.service.loop_replay = true;
    let port = free_port();
    let options = Options {
        config,
        camera: CameraSpec::Fake(concat!(env!("CARGO_MANIFEST_DIR"), "/fixtures/scenes").into()),
        link: LinkTarget::Serial(slave.name().unwrap()),
        baud: 115_200,
        faults: Faults::default(),
        frames: None,
        mcap: None,
        foxglove: Some(format!("127.0.0.1:{port}")),
    };
    let (stop_tx, stop_rx) = crossbeam_channel::bounded::<()>(1);

    // The pty reader: once warm, counts allocations and starts the viewer (its own
    // thread, named so its allocations are not counted); stops the service after.
    let reader = std::thread::spawn(move || {
        let mut decoder = Decoder::new();
        let mut buf = [0u8; 1024];
        let mut verdicts = 0usize;
        let mut client = None;
        while verdicts < WARM_UP + WATCHED {
            let Ok(n) = master.read(&mut buf) else {
                continue;
            };
            for &b in &buf[..n] {
                if let Some(Ok(Message::Verdict(_))) = decoder.push(b) {
                    verdicts += 1;
                    if verdicts == WARM_UP {
                        // Spawning allocates here: count from just after it.
                        client = Some(
                            std::thread::Builder::new()
                                .name("viewer-client".into())
                                .spawn(move || viewer(port, 3))
                                .unwrap(),
                        );
                        COUNTING.store(true, Ordering::SeqCst);
                    }
                }
            }
        }
        COUNTING.store(false, Ordering::SeqCst);
        let seen = client.map(|c| c.join().unwrap());
        drop(stop_tx);
        (verdicts, seen, master)
    });

    let summary = service::run(options, Notifier::disabled(), stop_rx).unwrap();
    let (verdicts, seen, _master) = reader.join().unwrap();
    drop(slave);

    assert_eq!(summary.reason, StopReason::Signal);
    let (live_verdicts, clouds) = seen.expect("the viewer ran");
    assert!(live_verdicts.len() >= 3);
    for v in &live_verdicts {
        assert!(v["verdict"].is_string() && v["frame"].is_u64(), "{v}");
    }
    assert!(clouds
        .iter()
        .all(|c| c.point_stride == 16 && !c.data.is_empty()));
    assert!(verdicts >= WARM_UP + WATCHED);
    assert_eq!(summary.link_dropped, 0, "every verdict reached the link");
    assert!(summary.viewer_written.is_some_and(|n| n > 0));
    assert_eq!(
        ALLOCATIONS.load(Ordering::SeqCst),
        0,
        "allocations in camera, analysis or link while a viewer came and went"
    );
}
