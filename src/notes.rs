//! Pages of the course notes that belong to no single question: the glossary every chapter links
//! to, and the engineering notes (how each chapter's timings were measured, the peer libraries it
//! was compared with, the designs it was measured against), kept out of the student's path.

/// The glossary: every technical term of the chapters, defined once.
pub mod glossary {
    #![doc = include_str!(concat!(env!("OUT_DIR"), "/glossary.md"))]
}

/// The homework: the student's handwritten answers, transcribed, which every chapter starts from.
pub mod homework {
    #![doc = include_str!(concat!(env!("OUT_DIR"), "/homework.md"))]
}

/// How a student hands in answers: the template, the answers file's forms, `hw3 check`.
pub mod hand_in {
    #![doc = include_str!(concat!(env!("OUT_DIR"), "/hand_in.md"))]
}

/// The printable answer key: every part's answer, the student's answer and its grade, and the
/// section that explains it.
pub mod answer_key {
    #![doc = include_str!(concat!(env!("OUT_DIR"), "/answer_key.md"))]
}

/// Engineering notes for Q1 (hard scenes): benchmark method, machine load, thread scaling.
pub mod engineering_q1 {
    #![doc = include_str!(concat!(env!("OUT_DIR"), "/engineering_q1.md"))]
}

/// Engineering notes for Q2 (ray/sphere): how the stable solver was made cheap, benchmarking traps.
pub mod engineering_q2 {
    #![doc = include_str!(concat!(env!("OUT_DIR"), "/engineering_q2.md"))]
}

/// Engineering notes for Q3 (kd-tree): the 3-D tree's build, peers, compile times, what made it fast.
pub mod engineering_q3 {
    #![doc = include_str!(concat!(env!("OUT_DIR"), "/engineering_q3.md"))]
}

/// Engineering notes for Q4 (light probe): the benchmark's maps, metrics and run-to-run noise.
pub mod engineering_q4 {
    #![doc = include_str!(concat!(env!("OUT_DIR"), "/engineering_q4.md"))]
}

/// Engineering notes for Q5 (effect tables): validation detail, solver timings, photon-map studies.
pub mod engineering_q5 {
    #![doc = include_str!(concat!(env!("OUT_DIR"), "/engineering_q5.md"))]
}

/// Engineering notes for the renderer: speed measurements, crates used, progress bar, plan timings.
pub mod engineering_render {
    #![doc = include_str!(concat!(env!("OUT_DIR"), "/engineering_render.md"))]
}
