//! Link the system libfreenect (Debian: `apt-get install libfreenect-dev`).
fn main() {
    if let Err(e) = pkg_config::Config::new()
        .atleast_version("0.5")
        .probe("libfreenect")
    {
        panic!(
            "libfreenect not found by pkg-config ({e}); install it with `apt-get install -y libfreenect-dev`, \
             or build without the `freenect` feature"
        );
    }
}
