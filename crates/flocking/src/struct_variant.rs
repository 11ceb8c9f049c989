//! serde for an enum variant that holds a struct but is written as a struct variant: `Vicsek(eta:
//! 2.0)` in RON, `{"Vicsek": {"eta": 2.0}}` in JSON, for `Algorithm::Vicsek(VicsekParams)`. The
//! struct keeps its own derived serde (field names, defaults, unknown fields refused), declared once
//! with the struct; these adapters only move its fields in and out of the variant.
//!
//! serde's derive writes a newtype variant as `Vicsek((eta: 2.0))`, and RON's
//! `unwrap_variant_newtypes` extension, which drops the inner parentheses, would drop them for every
//! newtype variant of a scenario (`vehicle: Quadrotor(())` would no longer read); `#[serde(flatten)]`
//! buffers the fields, losing the line and column of a bad value. Hence these adapters.

use std::marker::PhantomData;

use serde::de::value::MapAccessDeserializer;
use serde::de::{Deserialize, MapAccess, VariantAccess, Visitor};
use serde::ser::{
    Error, Impossible, Serialize, SerializeStruct, SerializeStructVariant, Serializer,
};

/// Writes `value`, a struct, as the struct variant `variant` (number `index`) of enum `name`.
///
/// # Errors
/// The serializer's, or one if `value` does not serialize as a struct.
pub(crate) fn serialize<T: Serialize + ?Sized, S: Serializer>(
    value: &T,
    serializer: S,
    name: &'static str,
    index: u32,
    variant: &'static str,
) -> Result<S::Ok, S::Error> {
    value.serialize(AsVariant {
        inner: serializer,
        name,
        index,
        variant,
    })
}

/// Reads the struct `T` from the fields of a struct variant.
///
/// # Errors
/// The deserializer's: a field unknown, missing or of the wrong type, at its line and column.
pub(crate) fn deserialize<'de, T: Deserialize<'de>, A: VariantAccess<'de>>(
    variant: A,
) -> Result<T, A::Error> {
    variant.struct_variant(&[], Fields(PhantomData))
}

/// The visitor of a struct variant's fields, handed to `T`'s own `Deserialize`.
struct Fields<T>(PhantomData<T>);

impl<'de, T: Deserialize<'de>> Visitor<'de> for Fields<T> {
    type Value = T;

    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("the fields of a struct variant")
    }

    fn visit_map<M: MapAccess<'de>>(self, map: M) -> Result<T, M::Error> {
        T::deserialize(MapAccessDeserializer::new(map))
    }
}

/// A serializer that writes the struct given to it as a struct variant of `inner`.
struct AsVariant<S> {
    inner: S,
    name: &'static str,
    index: u32,
    variant: &'static str,
}

/// The fields of the struct, written as the variant's.
struct VariantFields<S>(S);

impl<S: SerializeStructVariant> SerializeStruct for VariantFields<S> {
    type Ok = S::Ok;
    type Error = S::Error;

    fn serialize_field<T: Serialize + ?Sized>(
        &mut self,
        key: &'static str,
        value: &T,
    ) -> Result<(), S::Error> {
        self.0.serialize_field(key, value)
    }

    fn skip_field(&mut self, key: &'static str) -> Result<(), S::Error> {
        self.0.skip_field(key)
    }

    fn end(self) -> Result<S::Ok, S::Error> {
        self.0.end()
    }
}

/// The error of anything but a struct given to [`AsVariant`].
fn not_a_struct<E: Error, T>() -> Result<T, E> {
    Err(E::custom("a struct variant holds a struct"))
}

/// [`Serializer`] methods that refuse their value, for everything but a struct.
macro_rules! refuse {
    ($($method:ident($($arg:ty),*)),* $(,)?) => {
        $(fn $method(self, $(_: $arg),*) -> Result<S::Ok, S::Error> {
            not_a_struct()
        })*
    };
}

impl<S: Serializer> Serializer for AsVariant<S> {
    type Ok = S::Ok;
    type Error = S::Error;
    type SerializeSeq = Impossible<S::Ok, S::Error>;
    type SerializeTuple = Impossible<S::Ok, S::Error>;
    type SerializeTupleStruct = Impossible<S::Ok, S::Error>;
    type SerializeTupleVariant = Impossible<S::Ok, S::Error>;
    type SerializeMap = Impossible<S::Ok, S::Error>;
    type SerializeStruct = VariantFields<S::SerializeStructVariant>;
    type SerializeStructVariant = Impossible<S::Ok, S::Error>;

    fn serialize_struct(
        self,
        _name: &'static str,
        len: usize,
    ) -> Result<Self::SerializeStruct, S::Error> {
        self.inner
            .serialize_struct_variant(self.name, self.index, self.variant, len)
            .map(VariantFields)
    }

    fn is_human_readable(&self) -> bool {
        self.inner.is_human_readable()
    }

    refuse!(
        serialize_bool(bool),
        serialize_i8(i8),
        serialize_i16(i16),
        serialize_i32(i32),
        serialize_i64(i64),
        serialize_u8(u8),
        serialize_u16(u16),
        serialize_u32(u32),
        serialize_u64(u64),
        serialize_f32(f32),
        serialize_f64(f64),
        serialize_char(char),
        serialize_str(&str),
        serialize_bytes(&[u8]),
        serialize_none(),
        serialize_unit(),
        serialize_unit_struct(&'static str),
        serialize_unit_variant(&'static str, u32, &'static str),
    );

    fn serialize_some<T: Serialize + ?Sized>(self, _: &T) -> Result<S::Ok, S::Error> {
        not_a_struct()
    }

    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: &T,
    ) -> Result<S::Ok, S::Error> {
        not_a_struct()
    }

    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: &T,
    ) -> Result<S::Ok, S::Error> {
        not_a_struct()
    }

    fn serialize_seq(self, _: Option<usize>) -> Result<Self::SerializeSeq, S::Error> {
        not_a_struct()
    }

    fn serialize_tuple(self, _: usize) -> Result<Self::SerializeTuple, S::Error> {
        not_a_struct()
    }

    fn serialize_tuple_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleStruct, S::Error> {
        not_a_struct()
    }

    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleVariant, S::Error> {
        not_a_struct()
    }

    fn serialize_map(self, _: Option<usize>) -> Result<Self::SerializeMap, S::Error> {
        not_a_struct()
    }

    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeStructVariant, S::Error> {
        not_a_struct()
    }
}

/// Declares an enum of one unit variant and variants that each hold a struct, with the serde that
/// writes each as a struct variant ([`serialize`], [`deserialize`]): adding a variant is one line.
macro_rules! struct_variant_enum {
    (
        $(#[$meta:meta])*
        pub enum $name:ident {
            $(#[$unit_meta:meta])*
            $unit:ident,
            $(
                $(#[$variant_meta:meta])*
                $variant:ident($params:ty),
            )*
        }
    ) => {
        $(#[$meta])*
        pub enum $name {
            $(#[$unit_meta])*
            $unit,
            $(
                $(#[$variant_meta])*
                $variant($params),
            )*
        }

        const _: () = {
            use serde::de::{EnumAccess, VariantAccess, Visitor};
            use serde::{Deserialize, Deserializer, Serialize, Serializer};

            const NAME: &str = stringify!($name);
            const VARIANTS: &[&str] = &[stringify!($unit), $(stringify!($variant)),*];

            /// The variant a text names, numbered in the order of declaration.
            #[derive(Deserialize)]
            #[serde(variant_identifier)]
            enum Tag {
                $unit,
                $($variant),*
            }

            impl Serialize for $name {
                fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                    match self {
                        Self::$unit => {
                            s.serialize_unit_variant(NAME, Tag::$unit as u32, stringify!($unit))
                        }
                        $(Self::$variant(params) => $crate::struct_variant::serialize(
                            params,
                            s,
                            NAME,
                            Tag::$variant as u32,
                            stringify!($variant),
                        ),)*
                    }
                }
            }

            impl<'de> Deserialize<'de> for $name {
                fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                    d.deserialize_enum(NAME, VARIANTS, EnumVisitor)
                }
            }

            /// Reads the variant a text names, then its fields.
            struct EnumVisitor;

            impl<'de> Visitor<'de> for EnumVisitor {
                type Value = $name;

                fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                    write!(f, "one of {VARIANTS:?}")
                }

                fn visit_enum<A: EnumAccess<'de>>(self, data: A) -> Result<$name, A::Error> {
                    let (tag, variant) = data.variant::<Tag>()?;
                    Ok(match tag {
                        Tag::$unit => {
                            variant.unit_variant()?;
                            $name::$unit
                        }
                        $(Tag::$variant => {
                            $name::$variant($crate::struct_variant::deserialize(variant)?)
                        })*
                    })
                }
            }
        };
    };
}

pub(crate) use struct_variant_enum;
