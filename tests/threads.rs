//! The types a caller shares across threads are `Send + Sync`: the renderer, the photon tracer and
//! the figure jobs run on rayon's pool, and a library caller may do the same. Checked at compile
//! time, so a field that would break it (an `Rc`, a `Cell`) fails the build here, with the type
//! named, instead of in some caller's closure.
//!
//! The checks use static_assertions rather than a hand-written `fn is_send_sync<T: Send + Sync>()`
//! for a build reason: linked into the tests as the benchmarks' obvhs links it, it is built the
//! same way for both, so the benchmarks reuse the test build's math renderer and `hw3` instead of
//! compiling them again (`Cargo.toml`, at the dev-dependency, says more).

use static_assertions::assert_impl_all;

assert_impl_all!(hw3::kdtree::KdTree: Send, Sync);
assert_impl_all!(hw3::kdtree::KdTreeF32: Send, Sync);
assert_impl_all!(hw3::render::scene::Scene: Send, Sync);
assert_impl_all!(hw3::render::photon::PhotonMaps: Send, Sync);
assert_impl_all!(hw3::render::photon::PhotonMap: Send, Sync);
assert_impl_all!(hw3::envmap::Probe: Send, Sync);
assert_impl_all!(hw3::envmap::MapDistribution: Send, Sync);
