//! Embree 3 (the system's `libembree3`, Debian's `libembree-dev` 3.13.5) as a peer of the Q3
//! benchmark, through the few entry points it needs: one device on one thread, one scene of native
//! sphere points (`RTC_GEOMETRY_TYPE_SPHERE_POINT`, a centre and a radius per point), and
//! single-ray closest-hit queries (`rtcIntersect1`), and for the batch comparison the stream call
//! (`rtcIntersect1M`) and the 8-wide packet call (`rtcIntersect8`). Compiled only with the `embree` feature, so the
//! crate builds and the benchmark runs without the library.
//!
//! The declarations follow `embree3/rtcore_*.h` of 3.13.5 (`RTC_MAX_INSTANCE_LEVEL_COUNT = 1`,
//! `RTC_MIN_WIDTH = 0`); the layout test in [`Embree::new`] checks the two structures passed by
//! pointer against the header's sizes.

use std::ffi::{c_char, c_uint, c_void};
use std::ptr::NonNull;

/// `RTCRay`: origin, `tnear`, direction, time, `tfar` (shortened to the hit), mask, id, flags.
#[repr(C, align(16))]
#[derive(Debug, Clone, Copy, Default)]
struct RtcRay {
    org: [f32; 3],
    tnear: f32,
    dir: [f32; 3],
    time: f32,
    tfar: f32,
    mask: c_uint,
    id: c_uint,
    flags: c_uint,
}

/// `RTCHit`: geometric normal, barycentrics, primitive, geometry and instance ids.
#[repr(C, align(16))]
#[derive(Debug, Clone, Copy, Default)]
struct RtcHit {
    ng: [f32; 3],
    u: f32,
    v: f32,
    prim_id: c_uint,
    geom_id: c_uint,
    inst_id: [c_uint; 1],
}

#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
struct RtcRayHit {
    ray: RtcRay,
    hit: RtcHit,
}

/// `RTCRay8`: eight rays, structure of arrays.
#[repr(C, align(32))]
#[derive(Debug, Clone, Copy, Default)]
struct RtcRay8 {
    org: [[f32; 8]; 3],
    tnear: [f32; 8],
    dir: [[f32; 8]; 3],
    time: [f32; 8],
    tfar: [f32; 8],
    mask: [c_uint; 8],
    id: [c_uint; 8],
    flags: [c_uint; 8],
}

/// `RTCHit8`: eight hits, structure of arrays, one instance level.
#[repr(C, align(32))]
#[derive(Debug, Clone, Copy, Default)]
struct RtcHit8 {
    ng: [[f32; 8]; 3],
    u: [f32; 8],
    v: [f32; 8],
    prim_id: [c_uint; 8],
    geom_id: [c_uint; 8],
    inst_id: [[c_uint; 8]; 1],
}

#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
struct RtcRayHit8 {
    ray: RtcRay8,
    hit: RtcHit8,
}

/// `rtcIntersect8`'s `valid` mask: −1 for an active lane, 0 for an inactive one, 32-byte aligned.
#[repr(C, align(32))]
struct Valid8([i32; 8]);

/// `RTCIntersectContext` with one instance level and no minimum width.
#[repr(C)]
struct RtcIntersectContext {
    flags: c_uint,
    filter: *const c_void,
    inst_id: [c_uint; 1],
}

const RTC_INVALID_GEOMETRY_ID: c_uint = c_uint::MAX;
const RTC_GEOMETRY_TYPE_SPHERE_POINT: c_uint = 50;
const RTC_BUFFER_TYPE_VERTEX: c_uint = 1;
const RTC_FORMAT_FLOAT4: c_uint = 0x9004;
const RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT: c_uint = 0;
const RTC_INTERSECT_CONTEXT_FLAG_COHERENT: c_uint = 1;

#[link(name = "embree3")]
unsafe extern "C" {
    fn rtcNewDevice(config: *const c_char) -> *mut c_void;
    fn rtcReleaseDevice(device: *mut c_void);
    fn rtcGetDeviceError(device: *mut c_void) -> c_uint;
    fn rtcNewScene(device: *mut c_void) -> *mut c_void;
    fn rtcReleaseScene(scene: *mut c_void);
    fn rtcCommitScene(scene: *mut c_void);
    fn rtcNewGeometry(device: *mut c_void, kind: c_uint) -> *mut c_void;
    fn rtcSetNewGeometryBuffer(
        geometry: *mut c_void,
        kind: c_uint,
        slot: c_uint,
        format: c_uint,
        stride: usize,
        count: usize,
    ) -> *mut c_void;
    fn rtcCommitGeometry(geometry: *mut c_void);
    fn rtcAttachGeometry(scene: *mut c_void, geometry: *mut c_void) -> c_uint;
    fn rtcReleaseGeometry(geometry: *mut c_void);
    fn rtcIntersect1(scene: *mut c_void, context: *mut RtcIntersectContext, rayhit: *mut RtcRayHit);
    fn rtcIntersect1M(
        scene: *mut c_void,
        context: *mut RtcIntersectContext,
        rayhit: *mut RtcRayHit,
        count: c_uint,
        byte_stride: usize,
    );
    fn rtcIntersect8(
        valid: *const Valid8,
        scene: *mut c_void,
        context: *mut RtcIntersectContext,
        rayhit: *mut RtcRayHit8,
    );
}

/// An Embree device on one thread and a committed scene of sphere points.
pub struct Embree {
    device: NonNull<c_void>,
    scene: NonNull<c_void>,
}

impl Embree {
    /// Builds the scene (`centre_radius[i]` = x, y, z, r of sphere `i`, which Embree reports as
    /// primitive `i`).
    ///
    /// # Panics
    /// If Embree cannot create the device, scene or geometry, or reports an error.
    pub fn new(centre_radius: &[[f32; 4]]) -> Self {
        // The header's sizes: RTCRayHit 80 bytes (two 16-aligned halves of 48 and 32),
        // RTCIntersectContext 24 (flags, pointer, one instance id).
        assert_eq!((size_of::<RtcRayHit>(), size_of::<RtcIntersectContext>()), (80, 24));
        // RTCRayHit8: a 384-byte ray packet and a 256-byte hit packet, both 32-aligned.
        assert_eq!((size_of::<RtcRayHit8>(), align_of::<RtcRayHit8>()), (640, 32));
        let config = c"threads=1";
        // SAFETY: plain C calls on handles Embree returned; each is checked for null before use,
        // the vertex buffer is written within the `count` items Embree allocated for it.
        unsafe {
            let device = NonNull::new(rtcNewDevice(config.as_ptr())).expect("Embree device");
            let scene = NonNull::new(rtcNewScene(device.as_ptr())).expect("Embree scene");
            let geometry =
                NonNull::new(rtcNewGeometry(device.as_ptr(), RTC_GEOMETRY_TYPE_SPHERE_POINT)).expect("Embree geometry");
            let buffer = rtcSetNewGeometryBuffer(
                geometry.as_ptr(),
                RTC_BUFFER_TYPE_VERTEX,
                0,
                RTC_FORMAT_FLOAT4,
                size_of::<[f32; 4]>(),
                centre_radius.len(),
            )
            .cast::<[f32; 4]>();
            assert!(!buffer.is_null() || centre_radius.is_empty(), "Embree vertex buffer");
            if !centre_radius.is_empty() {
                std::ptr::copy_nonoverlapping(centre_radius.as_ptr(), buffer, centre_radius.len());
            }
            rtcCommitGeometry(geometry.as_ptr());
            let _ = rtcAttachGeometry(scene.as_ptr(), geometry.as_ptr());
            rtcReleaseGeometry(geometry.as_ptr());
            rtcCommitScene(scene.as_ptr());
            assert_eq!(rtcGetDeviceError(device.as_ptr()), 0, "Embree reported an error");
            Self { device, scene }
        }
    }

    /// The closest sphere point hit in `(t_min, ∞)`: primitive index and `t`. `coherent` sets
    /// Embree's hint for coherent rays (the camera's).
    pub fn closest_hit(&self, origin: [f32; 3], dir: [f32; 3], t_min: f32, coherent: bool) -> Option<(usize, f32)> {
        let mut context = context(coherent);
        let mut rayhit = ray_hit(origin, dir, t_min);
        // SAFETY: a committed scene and two initialised structures laid out as the header's.
        unsafe { rtcIntersect1(self.scene.as_ptr(), &raw mut context, &raw mut rayhit) };
        answer(&rayhit)
    }

    /// [`Embree::closest_hit`] for every ray of `rays` (origin, direction) with Embree's stream
    /// call `rtcIntersect1M` over one array of `RTCRayHit` (which, with the coherent hint, Embree
    /// regroups into packets itself).
    pub fn closest_hits_stream(
        &self,
        rays: &[([f32; 3], [f32; 3])],
        t_min: f32,
        coherent: bool,
    ) -> Vec<Option<(usize, f32)>> {
        let mut context = context(coherent);
        let mut rayhits: Vec<RtcRayHit> = rays.iter().map(|&(origin, dir)| ray_hit(origin, dir, t_min)).collect();
        for chunk in rayhits.chunks_mut(1 << 20) {
            // SAFETY: a committed scene, an initialised context, and `chunk.len()` (< 2³²)
            // initialised structures laid out as the header's, `size_of::<RtcRayHit>()` apart.
            unsafe {
                rtcIntersect1M(
                    self.scene.as_ptr(),
                    &raw mut context,
                    chunk.as_mut_ptr(),
                    chunk.len() as c_uint,
                    size_of::<RtcRayHit>(),
                );
            }
        }
        rayhits.iter().map(answer).collect()
    }

    /// [`Embree::closest_hit`] for every ray of `rays` with the 8-wide packet call `rtcIntersect8`,
    /// eight consecutive rays a packet (the last one padded with inactive lanes).
    pub fn closest_hits_packet8(
        &self,
        rays: &[([f32; 3], [f32; 3])],
        t_min: f32,
        coherent: bool,
    ) -> Vec<Option<(usize, f32)>> {
        let mut context = context(coherent);
        let mut hits = Vec::with_capacity(rays.len());
        for group in rays.chunks(8) {
            let mut packet = RtcRayHit8::default();
            let mut valid = Valid8([0; 8]);
            for (lane, &(origin, dir)) in group.iter().enumerate() {
                for a in 0..3 {
                    packet.ray.org[a][lane] = origin[a];
                    packet.ray.dir[a][lane] = dir[a];
                }
                packet.ray.tnear[lane] = t_min;
                packet.ray.tfar[lane] = f32::INFINITY;
                packet.ray.mask[lane] = u32::MAX;
                packet.hit.geom_id[lane] = RTC_INVALID_GEOMETRY_ID;
                packet.hit.inst_id[0][lane] = RTC_INVALID_GEOMETRY_ID;
                valid.0[lane] = -1;
            }
            // SAFETY: a committed scene, an initialised context, and an initialised, 32-aligned
            // valid mask and packet laid out as the header's (checked in `new`).
            unsafe { rtcIntersect8(&raw const valid, self.scene.as_ptr(), &raw mut context, &raw mut packet) };
            hits.extend((0..group.len()).map(|lane| {
                (packet.hit.geom_id[lane] != RTC_INVALID_GEOMETRY_ID)
                    .then_some((packet.hit.prim_id[lane] as usize, packet.ray.tfar[lane]))
            }));
        }
        hits
    }
}

/// An intersection context with the coherence hint and no filter.
fn context(coherent: bool) -> RtcIntersectContext {
    RtcIntersectContext {
        flags: if coherent { RTC_INTERSECT_CONTEXT_FLAG_COHERENT } else { RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT },
        filter: std::ptr::null(),
        inst_id: [RTC_INVALID_GEOMETRY_ID],
    }
}

/// A ray over `(t_min, ∞)` and an empty hit.
fn ray_hit(origin: [f32; 3], dir: [f32; 3], t_min: f32) -> RtcRayHit {
    RtcRayHit {
        ray: RtcRay { org: origin, tnear: t_min, dir, tfar: f32::INFINITY, mask: u32::MAX, ..RtcRay::default() },
        hit: RtcHit { geom_id: RTC_INVALID_GEOMETRY_ID, inst_id: [RTC_INVALID_GEOMETRY_ID], ..RtcHit::default() },
    }
}

/// The primitive and `t` of a traced ray, or `None` for a miss.
fn answer(rayhit: &RtcRayHit) -> Option<(usize, f32)> {
    (rayhit.hit.geom_id != RTC_INVALID_GEOMETRY_ID).then_some((rayhit.hit.prim_id as usize, rayhit.ray.tfar))
}

impl Drop for Embree {
    fn drop(&mut self) {
        // SAFETY: the handles were created in `new` and are released once.
        unsafe {
            rtcReleaseScene(self.scene.as_ptr());
            rtcReleaseDevice(self.device.as_ptr());
        }
    }
}
