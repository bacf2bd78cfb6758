//! Q2 timings with divan: the four intersection variants and the two spawn policies on the same
//! batch of 4096 camera rays. `cargo bench -p hw3-benches --bench q2_sphere`.
//! (The accuracy-versus-time table in the notes comes from `benches/q2_cost.rs`.)

use divan::black_box;
use hw3::geometry::sphere::first_hit_stable;
use hw3::geometry::{Ray, Sphere};
use hw3::q2_ray_sphere::catalogue::camera_batch;
use hw3::q2_ray_sphere::reflection::{SpawnPolicy, reflect_at_hit};
use hw3::q2_ray_sphere::student_solver::first_hit_naive;
use hw3::real::Real;

const BATCH: usize = 4096;

fn main() {
    divan::main();
}

fn batch<T: Real>() -> Vec<(Ray<T>, Sphere<T>)> {
    camera_batch(BATCH, 1)
        .into_iter()
        .map(|(r, s)| {
            (
                Ray { origin: T::vec_from_f64(r.origin), dir: T::vec_from_f64(r.dir) },
                Sphere { center: T::vec_from_f64(s.center), radius: T::from_f64(s.radius) },
            )
        })
        .collect()
}

fn sum_hits<T: Real>(pairs: &[(Ray<T>, Sphere<T>)], solver: fn(&Ray<T>, &Sphere<T>) -> Option<T>) -> T {
    pairs.iter().fold(T::ZERO, |acc, (ray, sphere)| acc + solver(black_box(ray), black_box(sphere)).unwrap_or(T::ZERO))
}

#[divan::bench(types = [f32, f64], counter = divan::counter::ItemsCount::new(BATCH))]
fn naive<T: Real>(bencher: divan::Bencher) {
    let pairs = batch::<T>();
    bencher.bench_local(|| sum_hits(&pairs, first_hit_naive::<T>));
}

#[divan::bench(types = [f32, f64], counter = divan::counter::ItemsCount::new(BATCH))]
fn stable<T: Real>(bencher: divan::Bencher) {
    let pairs = batch::<T>();
    bencher.bench_local(|| sum_hits(&pairs, first_hit_stable::<T>));
}

#[divan::bench(args = [SpawnPolicy::AtComputedPoint, SpawnPolicy::ReprojectAndOffset], counter = divan::counter::ItemsCount::new(BATCH))]
fn hit_and_reflect_f32(bencher: divan::Bencher, policy: SpawnPolicy) {
    let pairs = batch::<f32>();
    bencher.bench_local(|| {
        pairs.iter().fold(0.0f32, |acc, (ray, sphere)| match first_hit_stable(black_box(ray), sphere) {
            Some(t) => acc + reflect_at_hit(ray, sphere, t, black_box(policy)).ray.origin.x,
            None => acc,
        })
    });
}
