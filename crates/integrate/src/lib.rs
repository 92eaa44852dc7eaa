//! The flexdem engine (to come): collision detection, contact bookkeeping, parallel force
//! assembly, leapfrog integration with Cundall damping, and the critical time step.
