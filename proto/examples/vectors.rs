//! Prints PROTOCOL.md's test-vector table: `cargo run -p rover-terrain-proto --example vectors`.

fn main() {
    for (name, bytes) in rover_terrain_proto::vectors::table() {
        println!("| `{name}` | `{bytes}` |");
    }
}
