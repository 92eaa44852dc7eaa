//! The keys of the neighbour list's candidate pairs in 8 bytes each: a pair of free spheres
//! is `(Particle(i), Particle(j))`, a sphere and a wall `(Wall(w), Particle(i))`, so a key
//! is two ids and which of the two kinds it is. The list holds the sphere pairs first, then
//! the wall pairs (its keys are sorted, and every wall key sorts after every particle key),
//! so the kind is where the key stands: before or after [`PairKeys::first_wall`]. As
//! `(Feature, Feature)` a key took 16 bytes, 48 per sphere of a packing with its three
//! candidates per sphere.

use flexdem_elements::virtual_sphere::Feature;

/// The key of a contact: its two features (body 1's, body 2's).
pub type ContactKey = (Feature, Feature);

/// The candidate pairs' keys, in key order.
#[derive(Clone, Debug, Default)]
pub(crate) struct PairKeys {
    /// `(i, j)` of the sphere pairs, then `(w, i)` of the wall pairs.
    ids: Vec<(u32, u32)>,
    /// Where the wall pairs start.
    first_wall: usize,
    /// Whether a key the list cannot hold was pushed (neither kind, or a sphere pair after a
    /// wall pair: a checkpoint's list from elsewhere); it stands as `(u32::MAX, u32::MAX)`,
    /// and [`PairKeys::fits`] is false.
    foreign: bool,
}

/// The key of ids `ids` at index `n` of a list whose wall pairs start at `first_wall`.
#[inline(always)]
pub(crate) fn key_at(first_wall: usize, n: usize, ids: (u32, u32)) -> ContactKey {
    if n < first_wall {
        (Feature::Particle(ids.0), Feature::Particle(ids.1))
    } else {
        (Feature::Wall(ids.0), Feature::Particle(ids.1))
    }
}

impl PairKeys {
    /// Empty, with room for `n` keys.
    pub(crate) fn with_capacity(n: usize) -> Self {
        PairKeys { ids: Vec::with_capacity(n), first_wall: 0, foreign: false }
    }

    /// The keys of the candidates `spheres` (particle pairs, sorted; the array is kept for
    /// the keys, with room made for `walls`), then `walls` ((wall, particle) pairs, sorted),
    /// and the keys `extra` (sorted, none among the candidates) in their places.
    pub(crate) fn from_candidates(
        mut spheres: Vec<(u32, u32)>,
        walls: &[(u32, u32)],
        extra: &[ContactKey],
    ) -> Self {
        if extra.is_empty() {
            let first_wall = spheres.len();
            spheres.reserve_exact(walls.len());
            spheres.extend_from_slice(walls);
            return PairKeys { ids: spheres, first_wall, foreign: false };
        }
        let candidates = spheres
            .iter()
            .map(|&(i, j)| (Feature::Particle(i), Feature::Particle(j)))
            .chain(walls.iter().map(|&(w, i)| (Feature::Wall(w), Feature::Particle(i))));
        let mut keys = PairKeys::with_capacity(spheres.len() + walls.len() + extra.len());
        let mut extra = extra.iter().copied().peekable();
        for key in candidates {
            while let Some(k) = extra.next_if(|k| *k < key) {
                keys.push(k);
            }
            keys.push(key);
        }
        extra.for_each(|k| keys.push(k));
        keys
    }

    /// The number of keys.
    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.ids.len()
    }

    /// The key at index `n`.
    #[inline]
    pub(crate) fn get(&self, n: usize) -> ContactKey {
        key_at(self.first_wall, n, self.ids[n])
    }

    /// The key at index `n`, if there is one.
    #[inline]
    pub(crate) fn try_get(&self, n: usize) -> Option<ContactKey> {
        (n < self.len()).then(|| self.get(n))
    }

    /// The keys in order.
    pub(crate) fn iter(&self) -> impl Iterator<Item = ContactKey> + Clone + '_ {
        let first_wall = self.first_wall;
        self.ids.iter().enumerate().map(move |(n, &ids)| key_at(first_wall, n, ids))
    }

    /// The ids of the keys in order (kind by [`PairKeys::first_wall`], see [`key_at`]).
    pub(crate) fn ids(&self) -> &[(u32, u32)] {
        &self.ids
    }

    /// The index of the first wall pair (the number of sphere pairs).
    #[inline]
    pub(crate) fn first_wall(&self) -> usize {
        self.first_wall
    }

    /// Adds `key` at the end (keys come in order: sphere pairs, then wall pairs).
    pub(crate) fn push(&mut self, key: ContactKey) {
        match key {
            (Feature::Particle(i), Feature::Particle(j)) if self.first_wall == self.len() => {
                self.ids.push((i, j));
                self.first_wall += 1;
            }
            (Feature::Wall(w), Feature::Particle(i)) => self.ids.push((w, i)),
            _ => {
                self.foreign = true;
                self.ids.push((u32::MAX, u32::MAX));
            }
        }
    }

    /// No keys.
    pub(crate) fn clear(&mut self) {
        self.ids.clear();
        self.first_wall = 0;
        self.foreign = false;
    }

    /// Whether every key is held as it was pushed, refers to particles and walls of a model
    /// of `particles` particles and `walls` walls (free spheres `i < j`), and the keys are in
    /// strictly increasing order.
    pub(crate) fn fits(&self, particles: usize, walls: usize) -> bool {
        let (spheres, wall_pairs) = self.ids.split_at(self.first_wall);
        !self.foreign
            && spheres.iter().all(|&(i, j)| i < j && (j as usize) < particles)
            && wall_pairs.iter().all(|&(w, i)| (w as usize) < walls && (i as usize) < particles)
            && spheres.windows(2).all(|w| w[0] < w[1])
            && wall_pairs.windows(2).all(|w| w[0] < w[1])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn candidates_become_keys_in_their_own_array_and_extra_keys_go_in_their_places() {
        let p = Feature::Particle;
        let mut spheres = Vec::with_capacity(3);
        spheres.extend([(0, 3), (2, 5)]);
        let at = spheres.as_ptr();
        let keys = PairKeys::from_candidates(spheres, &[(0, 1)], &[]);
        assert_eq!(keys.ids(), [(0, 3), (2, 5), (0, 1)]);
        assert_eq!(keys.first_wall(), 2);
        // the candidates' array, which had room for the wall pair
        assert_eq!(keys.ids.as_ptr(), at);
        let extra =
            [(p(1), p(2)), (p(4), p(6)), (Feature::Wall(0), p(0)), (Feature::Wall(2), p(2))];
        let keys = PairKeys::from_candidates(vec![(0, 3), (2, 5)], &[(0, 1)], &extra);
        let want = [
            (p(0), p(3)),
            (p(1), p(2)),
            (p(2), p(5)),
            (p(4), p(6)),
            (Feature::Wall(0), p(0)),
            (Feature::Wall(0), p(1)),
            (Feature::Wall(2), p(2)),
        ];
        assert_eq!(keys.iter().collect::<Vec<_>>(), want);
        assert_eq!(keys.first_wall(), 4);
        assert!(keys.fits(7, 3));
    }

    #[test]
    fn keys_come_back_as_pushed_and_in_the_order_of_features() {
        let p = Feature::Particle;
        let keys = [(p(0), p(3)), (p(2), p(5)), (Feature::Wall(0), p(1)), (Feature::Wall(1), p(0))];
        let mut list = PairKeys::with_capacity(4);
        keys.iter().for_each(|&k| list.push(k));
        assert_eq!(list.iter().collect::<Vec<_>>(), keys);
        assert_eq!((list.first_wall(), list.get(2), list.try_get(4)), (2, keys[2], None));
        assert!(keys.windows(2).all(|w| w[0] < w[1]));
        assert!(list.fits(6, 2) && !list.fits(5, 2) && !list.fits(6, 1));
        // a key the list cannot hold keeps its place, and the list does not fit
        let mut odd = list.clone();
        odd.push((Feature::Edge(1), p(2)));
        assert_eq!(odd.len(), 5);
        assert!(!odd.fits(6, 2));
        let mut late = list.clone();
        late.push((p(7), p(8)));
        assert!(!late.fits(9, 2));
        list.clear();
        assert_eq!((list.len(), list.first_wall()), (0, 0));
    }
}
