//! The flexdem contact law (paper §2–3): materials, stiffnesses (eq 3, 4, 8), the force and
//! moment update of one contact or beam link with plastic limits and breakage (eq 1–2, 5–7),
//! and energy terms. Pure functions over contact state; the engine only calls them.
