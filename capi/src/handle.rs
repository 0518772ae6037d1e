//! Objects in storage the caller owns: the tag word that makes a bad handle an error code,
//! and the crate's `unsafe`, all of it here.
//!
//! A storage struct (`StiffspringValueF32`, ...) is an array of `u64` words, so that C
//! gives it the alignment of `uint64_t` (8 on the Cortex-M EABI and on 64-bit hosts). In
//! Rust the words are `MaybeUninit<u64>` (which cbindgen writes as `uint64_t`): an object's
//! padding bytes are uninitialised, and a Rust copy of the storage as plain `u64`s would
//! read them (Miri found this).
//! Inside it lies a [`Slot`]: a tag word, then the Rust object. The tag is
//! [`Tag::live`] of the type while the object lives and [`Tag::dropped`] after its `drop`;
//! anything else (zeroed storage, another type's object, garbage) is no object of the type.
//! One header serves every target: the storage is at least as large as the object on the
//! largest (a compile-time assertion in each module checks it on the target being built).
//!
//! **The contract a C caller keeps** (the header says it on every function): a non-null
//! handle points to storage of its type that the caller owns for the duration of the call,
//! and no other call uses the same object at the same time. Everything else is checked.

use crate::error::StiffspringError;
use core::mem::{MaybeUninit, align_of, size_of};

/// A zeroed word of storage, as a C `static` or `= {0}` gives.
pub const ZERO: MaybeUninit<u64> = MaybeUninit::new(0);

/// The alignment of every storage struct: that of `uint64_t`.
pub const STIFFSPRING_STORAGE_ALIGN: usize = 8;

/// One object type's tags: its live tag, and the tag its `drop` leaves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tag(u32);

impl Tag {
    /// The tag of object type `id` (a small integer per type): the ASCII `"ss"` and the id,
    /// so that zeroed or random storage is unlikely to carry it.
    pub const fn new(id: u16) -> Tag {
        Tag(0x7373_0000 | id as u32)
    }

    /// The word a live object's storage begins with.
    pub const fn live(self) -> u32 {
        self.0
    }

    /// The word a dropped object's storage begins with.
    pub const fn dropped(self) -> u32 {
        !self.0
    }
}

/// What lies in the storage: the tag, then the object.
#[repr(C)]
pub struct Slot<T> {
    tag: u32,
    object: T,
}

/// Whether a `Slot<T>` fits in `size` bytes aligned to [`STIFFSPRING_STORAGE_ALIGN`]: the
/// compile-time check each storage type makes.
pub const fn fits<T>(size: usize) -> bool {
    size_of::<Slot<T>>() <= size && align_of::<Slot<T>>() <= STIFFSPRING_STORAGE_ALIGN
}

/// Why `storage` cannot hold a `Slot<T>`, if it cannot: null or misaligned.
fn check_pointer<T>(storage: *const u8) -> Result<(), StiffspringError> {
    if storage.is_null() {
        Err(StiffspringError::NullPointer)
    } else if !(storage as usize).is_multiple_of(align_of::<Slot<T>>()) {
        Err(StiffspringError::Misaligned)
    } else {
        Ok(())
    }
}

/// Writes `make()`'s object into `storage` of `size` bytes under `tag`. When `make` fails
/// the storage is left as it was, and its error returned.
///
/// # Safety
///
/// `storage` is null or valid for writes of `size` bytes, and nothing else uses those
/// bytes during the call.
pub unsafe fn init<T>(
    storage: *mut u8,
    size: usize,
    tag: Tag,
    make: impl FnOnce() -> Result<T, StiffspringError>,
) -> Result<(), StiffspringError> {
    check_pointer::<T>(storage)?;
    if size < size_of::<Slot<T>>() {
        return Err(StiffspringError::BufferTooSmall);
    }
    let object = make()?;
    // SAFETY: `storage` is non-null and aligned for `Slot<T>` (checked above), valid for
    // `size ≥ size_of::<Slot<T>>()` bytes of writes (checked above, and the caller's
    // contract), and not in use elsewhere (the contract). `write` does not read or drop the
    // old bytes, which may be anything.
    unsafe {
        storage.cast::<Slot<T>>().write(Slot {
            tag: tag.live(),
            object,
        })
    };
    Ok(())
}

/// [`init`] for an object too large to move: `make` builds the library's object in the
/// storage itself (as `SpringBatch::new_in` does) instead of returning it, so that no copy
/// of it is made (the copy was a `memcpy` of the whole batch, and the `memcpy` itself,
/// in a C firmware's flash). The tag becomes live last.
///
/// # Safety
///
/// As [`init`]; and `make` writes its slot only when it returns `Ok` (as the library's
/// in-place constructors do), so that on an error the storage, and an object that may
/// live there, are as they were.
pub unsafe fn init_in_place<T>(
    storage: *mut u8,
    size: usize,
    tag: Tag,
    make: impl FnOnce(&mut MaybeUninit<T>) -> Result<&mut T, StiffspringError>,
) -> Result<(), StiffspringError> {
    check_pointer::<T>(storage)?;
    if size < size_of::<Slot<T>>() {
        return Err(StiffspringError::BufferTooSmall);
    }
    let slot = storage.cast::<Slot<T>>();
    // SAFETY: `storage` is non-null, aligned for the slot and `size` bytes long (checked
    // above, and the contract), and nothing else uses it (the contract): the object's
    // field is in bounds, and a `&mut MaybeUninit<T>` to it asks nothing of its bytes
    // (`MaybeUninit<T>` has `T`'s layout).
    let object = unsafe { &mut *(&raw mut (*slot).object).cast::<MaybeUninit<T>>() };
    let expected: *const T = object.as_ptr();
    // `make` writes nothing when it fails (the contract), so `?` leaves the storage as it was.
    let built: *const T = make(object)?;
    if !core::ptr::eq(built, expected) {
        // An object built elsewhere: the slot's bytes are not known to be one, so the
        // storage holds none now (this does not happen with the library's constructors).
        // SAFETY: the tag is in bounds of the storage, which is ours (as above).
        unsafe { (&raw mut (*slot).tag).write(0) };
        return Err(StiffspringError::Other);
    }
    // SAFETY: in bounds and ours (as above). With the `T` that `make` returned, a
    // reference to the slot's own object, the slot is whole, and the tag says so last.
    unsafe { (&raw mut (*slot).tag).write(tag.live()) };
    Ok(())
}

/// Whether a live `T` is in `storage`, by its tag.
///
/// # Safety
///
/// `storage` is null or points to storage of `T`'s type (at least a `Slot<T>`, as the
/// type's storage struct is) that the caller owns and nothing writes during the call.
unsafe fn check_live<T>(storage: *const u8, tag: Tag) -> Result<(), StiffspringError> {
    check_pointer::<T>(storage)?;
    let slot = storage.cast::<Slot<T>>();
    // SAFETY: non-null and aligned (checked above); the tag is the first word of the
    // storage the caller owns (the contract), and reading a `u32` accepts any bytes.
    let word = unsafe { (&raw const (*slot).tag).read() };
    if word == tag.live() {
        Ok(())
    } else {
        Err(not_live(word, tag))
    }
}

/// Why storage whose tag is `word` holds no live object: out of the hot path, so that a
/// call on a live object tests its tag with one compare (it saves 8 instructions a call).
#[cold]
#[inline(never)]
fn not_live(word: u32, tag: Tag) -> StiffspringError {
    if word == tag.dropped() {
        StiffspringError::Dropped
    } else {
        StiffspringError::NotInitialised
    }
}

/// The object of type `T` in `storage`, if its tag says one lives there.
///
/// # Safety
///
/// `storage` is null or points to storage of `T`'s type (at least a `Slot<T>`, as the
/// type's storage struct is) that the caller owns and nothing else uses during the call,
/// and the lifetime `'a` ends before the call returns to C.
pub unsafe fn get<'a, T>(storage: *mut u8, tag: Tag) -> Result<&'a mut T, StiffspringError> {
    // SAFETY: the caller's contract covers `check_live`'s.
    unsafe { check_live::<T>(storage, tag) }?;
    // SAFETY: the live tag is written only by `init`, together with a valid `T`, and only
    // `drop` (which changes the tag) ends it, so a `T` lives here; the caller's contract
    // makes this the only reference to it during the call.
    Ok(unsafe { &mut (*storage.cast::<Slot<T>>()).object })
}

/// [`get`] for reading: the object of type `T` in `storage`, shared.
///
/// # Safety
///
/// As [`get`], except that other readers may share the object during the call.
pub unsafe fn get_ref<'a, T>(storage: *const u8, tag: Tag) -> Result<&'a T, StiffspringError> {
    // SAFETY: the caller's contract covers `check_live`'s.
    unsafe { check_live::<T>(storage, tag) }?;
    // SAFETY: a live `T` is here (as in `get`), and nothing writes it during the call.
    Ok(unsafe { &(*storage.cast::<Slot<T>>()).object })
}

/// Ends the object in `storage`: its tag becomes [`Tag::dropped`], so that a later use
/// returns [`StiffspringError::Dropped`] until it is initialised again.
///
/// # Safety
///
/// As [`get`].
pub unsafe fn drop<T>(storage: *mut u8, tag: Tag) -> Result<(), StiffspringError> {
    // SAFETY: the caller's contract is `get`'s.
    let object: *mut T = unsafe { get::<T>(storage, tag) }?;
    // SAFETY: `object` is the live `T` (found by `get`), dropped once: the tag changes
    // right after, so no later call reaches it again. (The library's objects own no
    // resources; this is for form.)
    unsafe { object.drop_in_place() };
    // SAFETY: `storage` is non-null, aligned and owned by the caller (checked by `get`).
    unsafe { (&raw mut (*storage.cast::<Slot<T>>()).tag).write(tag.dropped()) };
    Ok(())
}

/// Writes `value` to the out-pointer `out`; null and misaligned pointers are errors.
///
/// # Safety
///
/// `out` is null or valid for a write of a `T`.
pub unsafe fn write_out<T>(out: *mut T, value: T) -> Result<(), StiffspringError> {
    if out.is_null() {
        return Err(StiffspringError::NullPointer);
    }
    if !(out as usize).is_multiple_of(align_of::<T>()) {
        return Err(StiffspringError::Misaligned);
    }
    // SAFETY: non-null and aligned (checked above), valid for a write (the contract).
    // `write` drops nothing: out-values are plain data.
    unsafe { out.write(value) };
    Ok(())
}

/// Writes `value` to `out` unless `out` is null (an out-pointer the caller may omit).
///
/// # Safety
///
/// As [`write_out`].
pub unsafe fn write_optional<T>(out: *mut T, value: T) -> Result<(), StiffspringError> {
    if out.is_null() {
        return Ok(());
    }
    // SAFETY: the caller's contract is `write_out`'s.
    unsafe { write_out(out, value) }
}

/// Reads the `T` at `input`; null and misaligned pointers are errors.
///
/// # Safety
///
/// `input` is null or valid for a read of an initialised `T`.
pub unsafe fn read_in<T: Copy>(input: *const T) -> Result<T, StiffspringError> {
    if input.is_null() {
        return Err(StiffspringError::NullPointer);
    }
    if !(input as usize).is_multiple_of(align_of::<T>()) {
        return Err(StiffspringError::Misaligned);
    }
    // SAFETY: non-null and aligned (checked above), valid for a read of a `T` (the
    // contract); `T: Copy`, so reading leaves the original usable.
    Ok(unsafe { input.read() })
}

/// Whether storage that nothing was written to is still all zero (the tests' check that a
/// refused call wrote nothing).
#[cfg(test)]
pub(crate) fn is_zero(words: &[MaybeUninit<u64>]) -> bool {
    // SAFETY: the tests call this on storage they zeroed; were an object written there,
    // its padding would be read uninitialised, which Miri reports as the bug it would be.
    words.iter().all(|w| unsafe { w.assume_init() } == 0)
}

#[cfg(test)]
mod tests {
    use super::*;

    const TAG: Tag = Tag::new(0xfe);
    const OTHER: Tag = Tag::new(0xfd);

    /// Storage of four words, as a C caller declares it.
    #[repr(C)]
    struct Storage([u64; 4]);

    fn storage() -> Storage {
        Storage([0; 4])
    }

    fn ptr(s: &mut Storage) -> *mut u8 {
        s.0.as_mut_ptr().cast()
    }

    #[test]
    fn an_object_lives_between_init_and_drop() {
        let mut s = storage();
        let p = ptr(&mut s);
        // SAFETY: `p` is 32 bytes of our storage, nothing else uses it.
        unsafe {
            assert_eq!(get::<u64>(p, TAG), Err(StiffspringError::NotInitialised));
            assert_eq!(init(p, 32, TAG, || Ok(7u64)), Ok(()));
            *get::<u64>(p, TAG).unwrap() += 1;
            assert_eq!(*get::<u64>(p, TAG).unwrap(), 8);
            assert_eq!(get::<u64>(p, OTHER), Err(StiffspringError::NotInitialised));
            assert_eq!(drop::<u64>(p, TAG), Ok(()));
            assert_eq!(get::<u64>(p, TAG), Err(StiffspringError::Dropped));
            assert_eq!(drop::<u64>(p, TAG), Err(StiffspringError::Dropped));
            assert_eq!(init(p, 32, TAG, || Ok(1u64)), Ok(()));
            assert_eq!(*get::<u64>(p, TAG).unwrap(), 1);
        }
    }

    #[test]
    fn bad_storage_is_refused_before_it_is_touched() {
        let mut s = storage();
        let p = ptr(&mut s);
        // SAFETY: every pointer is null or into our 32 bytes; a refused call writes nothing.
        unsafe {
            let null = core::ptr::null_mut();
            assert_eq!(
                init(null, 32, TAG, || Ok(0u64)),
                Err(StiffspringError::NullPointer)
            );
            assert_eq!(get::<u64>(null, TAG), Err(StiffspringError::NullPointer));
            assert_eq!(
                init(p, 15, TAG, || Ok(0u64)),
                Err(StiffspringError::BufferTooSmall)
            );
            assert_eq!(
                init(p.add(4), 24, TAG, || Ok(0u64)),
                Err(StiffspringError::Misaligned)
            );
            assert_eq!(get::<u64>(p.add(4), TAG), Err(StiffspringError::Misaligned));
            let failing = init::<u64>(p, 32, TAG, || Err(StiffspringError::NotFinite));
            assert_eq!(failing, Err(StiffspringError::NotFinite));
        }
        assert_eq!(s.0, [0; 4]);
    }

    #[test]
    fn out_pointers_are_checked() {
        let mut words = [0u32; 2];
        // SAFETY: null, or into `words`.
        unsafe {
            assert_eq!(
                write_out(core::ptr::null_mut::<u32>(), 1),
                Err(StiffspringError::NullPointer)
            );
            assert_eq!(write_optional(core::ptr::null_mut::<u32>(), 1), Ok(()));
            let odd = words.as_mut_ptr().cast::<u8>().add(1).cast::<u32>();
            assert_eq!(write_out(odd, 1), Err(StiffspringError::Misaligned));
            assert_eq!(write_out(words.as_mut_ptr().add(1), 5), Ok(()));
            assert_eq!(read_in(words.as_ptr().add(1)), Ok(5));
            assert_eq!(
                read_in(core::ptr::null::<u32>()),
                Err(StiffspringError::NullPointer)
            );
        }
    }

    #[test]
    fn tags_differ_from_zeroed_storage_and_each_other() {
        assert_ne!(TAG.live(), 0);
        assert_ne!(TAG.dropped(), 0);
        assert_ne!(TAG.live(), OTHER.live());
        assert_ne!(TAG.live(), TAG.dropped());
    }
}

/// The storage structs are no larger than the objects need on a 64-bit host (the largest
/// target), so that a firmware declares no bytes it does not use.
#[cfg(all(test, target_pointer_width = "64"))]
mod storage_sizes {
    use super::Slot;
    use core::mem::size_of;

    fn words<T>() -> usize {
        size_of::<Slot<T>>().div_ceil(8)
    }

    #[test]
    fn each_storage_has_the_words_of_its_object() {
        use crate::{batch, knob, knob_config, tuning, value};
        use stiffspring::{I16F16, Knob, KnobConfig, SpringValue, Tuning};
        assert_eq!(tuning::STIFFSPRING_TUNING_WORDS, words::<Tuning>());
        assert_eq!(
            value::STIFFSPRING_VALUE_F32_WORDS,
            words::<SpringValue<f32>>()
        );
        assert_eq!(
            value::STIFFSPRING_VALUE_Q16_WORDS,
            words::<SpringValue<I16F16>>()
        );
        assert_eq!(batch::STIFFSPRING_BATCH_F32_WORDS, batch::words::<f32>());
        assert_eq!(batch::STIFFSPRING_BATCH_Q16_WORDS, batch::words::<I16F16>());
        assert_eq!(
            knob_config::STIFFSPRING_KNOB_CONFIG_WORDS,
            words::<KnobConfig>()
        );
        assert_eq!(knob::STIFFSPRING_KNOB_F32_WORDS, words::<Knob<f32>>());
        assert_eq!(knob::STIFFSPRING_KNOB_Q16_WORDS, words::<Knob<I16F16>>());
    }
}
