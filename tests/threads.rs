//! The types a caller shares across threads are `Send + Sync`: the renderer, the photon tracer and
//! the figure jobs run on rayon's pool, and a library caller may do the same. Checked at compile
//! time, so a field that would break it (an `Rc`, a `Cell`) fails the build here, with the type
//! named, instead of in some caller's closure.
//!
//! (static_assertions is also why this file's checks use a crate rather than a hand-written
//! `fn is_send_sync<T: Send + Sync>()`: as a dev-dependency it is linked into the tests the way the
//! benchmarks' obvhs links it, so `cargo test` and the benchmarks build it, and the docs' math
//! renderer above it, once; `Cargo.toml` says more.)

use static_assertions::assert_impl_all;

assert_impl_all!(hw3::kdtree::KdTree: Send, Sync);
assert_impl_all!(hw3::kdtree::KdTreeF32: Send, Sync);
assert_impl_all!(hw3::render::scene::Scene: Send, Sync);
assert_impl_all!(hw3::render::photon::PhotonMaps: Send, Sync);
assert_impl_all!(hw3::render::photon::PhotonMap: Send, Sync);
assert_impl_all!(hw3::envmap::Probe: Send, Sync);
assert_impl_all!(hw3::envmap::MapDistribution: Send, Sync);
