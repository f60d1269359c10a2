//! The layout of each `#[repr(C)]` parameter struct written into a shader's uniform block, and
//! the WGSL struct it binds to there. Declared next to the struct, listed by the catalogue entry
//! that uses it; `uniform_layout_tests.rs` compares each with the layout naga computes for the
//! WGSL struct.

/// A Rust struct's size and the offsets of its named fields (padding fields, whose names start
/// with `_`, count in the size only). Built with `rust_layout!`.
#[derive(Clone, Copy, Debug)]
pub struct RustLayout {
    pub name: &'static str,
    pub size: usize,
    pub fields: &'static [FieldLayout],
}

/// One named field of a [`RustLayout`].
#[derive(Clone, Copy, Debug)]
pub struct FieldLayout {
    /// The same name as the WGSL member.
    pub name: &'static str,
    pub offset: usize,
    pub size: usize,
}

/// A Rust struct and the WGSL struct it is written into in one shader.
#[derive(Clone, Copy, Debug)]
pub struct UniformLayout {
    pub rust: RustLayout,
    /// The WGSL struct's name.
    pub wgsl: &'static str,
    /// The shader (path under `shaders/`) that binds it.
    pub shader: &'static str,
}

/// The size of the field `field` picks, for `rust_layout!` (usable in constants).
pub const fn field_size<T, F>(_field: fn(&T) -> &F) -> usize {
    std::mem::size_of::<F>()
}

/// `rust_layout!(Params { key, values })`: the [`RustLayout`] of `Params` with its named fields,
/// each as the WGSL struct names it; leave out the padding.
macro_rules! rust_layout {
    ($ty:ident { $($field:ident),+ $(,)? }) => {
        $crate::uniform_layout::RustLayout {
            name: stringify!($ty),
            size: ::std::mem::size_of::<$ty>(),
            fields: &[$($crate::uniform_layout::FieldLayout {
                name: stringify!($field),
                offset: ::std::mem::offset_of!($ty, $field),
                size: $crate::uniform_layout::field_size(|s: &$ty| &s.$field),
            }),+],
        }
    };
}
pub(crate) use rust_layout;
