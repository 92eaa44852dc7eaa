//! Deformable structures for flexdem (paper §3–5): nodes, connections, PFacets, walls,
//! builders, mass lumping and the virtual-sphere kinematics that reduce every pair to a
//! sphere–sphere contact.
