//! Blocked degrees of freedom of a 6-DOF body, as a small bitset.
//!
//! YADE's semantics: a blocked DOF keeps its current velocity component (0, or an imposed
//! value); forces do not change it. The textual form is YADE's `blockedDOFs`: lowercase
//! `x`, `y`, `z` for translations, uppercase `X`, `Y`, `Z` for rotations about those axes.

use serde::{Deserialize, Serialize};
use std::fmt;
use std::ops::{BitAnd, BitOr, BitOrAssign, Not};
use std::str::FromStr;

/// A set of degrees of freedom: translations x, y, z and rotations rx, ry, rz.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Dofs(u8);

impl Dofs {
    /// No DOF.
    pub const NONE: Dofs = Dofs(0);
    /// Translation along x.
    pub const X: Dofs = Dofs(1);
    /// Translation along y.
    pub const Y: Dofs = Dofs(1 << 1);
    /// Translation along z.
    pub const Z: Dofs = Dofs(1 << 2);
    /// Rotation about x.
    pub const RX: Dofs = Dofs(1 << 3);
    /// Rotation about y.
    pub const RY: Dofs = Dofs(1 << 4);
    /// Rotation about z.
    pub const RZ: Dofs = Dofs(1 << 5);
    /// The three translations (`"xyz"`).
    pub const TRANSLATION: Dofs = Dofs(0b000_111);
    /// The three rotations (`"XYZ"`).
    pub const ROTATION: Dofs = Dofs(0b111_000);
    /// All six DOFs (`"xyzXYZ"`).
    pub const ALL: Dofs = Dofs(0b111_111);

    /// The letters of the textual form, in bit order.
    const LETTERS: [char; 6] = ['x', 'y', 'z', 'X', 'Y', 'Z'];

    /// The translation along axis `axis` (0 = x, 1 = y, 2 = z); `NONE` for other values.
    pub fn translation(axis: usize) -> Dofs {
        if axis < 3 {
            Dofs(1 << axis)
        } else {
            Dofs::NONE
        }
    }

    /// The rotation about axis `axis` (0 = x, 1 = y, 2 = z); `NONE` for other values.
    pub fn rotation(axis: usize) -> Dofs {
        if axis < 3 {
            Dofs(1 << (axis + 3))
        } else {
            Dofs::NONE
        }
    }

    /// Whether every DOF of `other` is in `self`.
    pub fn contains(self, other: Dofs) -> bool {
        self.0 & other.0 == other.0
    }

    /// Whether `self` and `other` share a DOF.
    pub fn intersects(self, other: Dofs) -> bool {
        self.0 & other.0 != 0
    }

    /// Whether the set is empty.
    pub fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// The DOFs of `self` not in `other`.
    pub fn difference(self, other: Dofs) -> Dofs {
        Dofs(self.0 & !other.0)
    }

    /// The raw bits (x = bit 0 … rz = bit 5).
    pub fn bits(self) -> u8 {
        self.0
    }

    /// The set with these bits; bits above 5 are dropped.
    pub fn from_bits_truncate(bits: u8) -> Dofs {
        Dofs(bits & Dofs::ALL.0)
    }
}

impl BitOr for Dofs {
    type Output = Dofs;
    fn bitor(self, rhs: Dofs) -> Dofs {
        Dofs(self.0 | rhs.0)
    }
}

impl BitOrAssign for Dofs {
    fn bitor_assign(&mut self, rhs: Dofs) {
        self.0 |= rhs.0;
    }
}

impl BitAnd for Dofs {
    type Output = Dofs;
    fn bitand(self, rhs: Dofs) -> Dofs {
        Dofs(self.0 & rhs.0)
    }
}

impl Not for Dofs {
    type Output = Dofs;
    fn not(self) -> Dofs {
        Dofs(!self.0 & Dofs::ALL.0)
    }
}

/// A `blockedDOFs` string with a character that is not one of `xyzXYZ`.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "invalid DOF letter {letter:?} at position {position} in {text:?}: expected only the letters \
     x, y, z (translations) and X, Y, Z (rotations), e.g. \"xyzXYZ\""
)]
pub struct DofsParseError {
    /// The whole string.
    pub text: String,
    /// The offending character.
    pub letter: char,
    /// Its character index in `text`.
    pub position: usize,
}

impl FromStr for Dofs {
    type Err = DofsParseError;

    /// Parses YADE's `blockedDOFs` form: any of `x y z X Y Z`, in any order, repeats allowed;
    /// the empty string is [`Dofs::NONE`].
    fn from_str(text: &str) -> Result<Dofs, DofsParseError> {
        let mut dofs = Dofs::NONE;
        for (position, letter) in text.chars().enumerate() {
            match Dofs::LETTERS.iter().position(|&l| l == letter) {
                Some(bit) => dofs |= Dofs(1 << bit),
                None => {
                    return Err(DofsParseError { text: text.to_owned(), letter, position });
                }
            }
        }
        Ok(dofs)
    }
}

impl fmt::Display for Dofs {
    /// The `blockedDOFs` form, letters in the order `xyzXYZ` (empty for [`Dofs::NONE`]).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (bit, letter) in Dofs::LETTERS.iter().enumerate() {
            if self.0 & (1 << bit) != 0 {
                write!(f, "{letter}")?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_all_and_subsets() {
        assert_eq!("xyzXYZ".parse::<Dofs>().unwrap(), Dofs::ALL);
        assert_eq!("xyz".parse::<Dofs>().unwrap(), Dofs::TRANSLATION);
        assert_eq!("XYZ".parse::<Dofs>().unwrap(), Dofs::ROTATION);
        assert_eq!("".parse::<Dofs>().unwrap(), Dofs::NONE);
        assert_eq!("zX".parse::<Dofs>().unwrap(), Dofs::Z | Dofs::RX);
        assert_eq!("xx".parse::<Dofs>().unwrap(), Dofs::X);
        // YADE's 'xyzXZ' from the PFacet examples: rotation about y free.
        let d: Dofs = "xyzXZ".parse().unwrap();
        assert!(d.contains(Dofs::TRANSLATION));
        assert!(!d.contains(Dofs::RY));
        assert!(d.contains(Dofs::RX | Dofs::RZ));
    }

    #[test]
    fn parse_rejects_unknown_letter_and_names_it() {
        let err = "xyw".parse::<Dofs>().unwrap_err();
        assert_eq!(err.letter, 'w');
        assert_eq!(err.position, 2);
        let msg = err.to_string();
        assert!(msg.contains("'w'") && msg.contains("position 2"), "{msg}");
        assert!(" x".parse::<Dofs>().is_err());
    }

    #[test]
    fn display_round_trips_every_subset() {
        for bits in 0..64u8 {
            let d = Dofs::from_bits_truncate(bits);
            assert_eq!(d.to_string().parse::<Dofs>().unwrap(), d);
        }
        assert_eq!(Dofs::ALL.to_string(), "xyzXYZ");
        assert_eq!((Dofs::Y | Dofs::RZ).to_string(), "yZ");
    }

    #[test]
    fn set_operations() {
        assert!(Dofs::ALL.contains(Dofs::TRANSLATION));
        assert!(!Dofs::TRANSLATION.contains(Dofs::ALL));
        assert!(Dofs::NONE.is_empty());
        assert_eq!(!Dofs::TRANSLATION, Dofs::ROTATION);
        assert_eq!(Dofs::ALL.difference(Dofs::ROTATION), Dofs::TRANSLATION);
        assert_eq!(Dofs::translation(1), Dofs::Y);
        assert_eq!(Dofs::rotation(2), Dofs::RZ);
        assert_eq!(Dofs::translation(3), Dofs::NONE);
        assert!(Dofs::X.intersects(Dofs::TRANSLATION));
        assert!(!Dofs::X.intersects(Dofs::ROTATION));
    }
}
