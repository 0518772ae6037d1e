//! The haptic knob (work in progress).
