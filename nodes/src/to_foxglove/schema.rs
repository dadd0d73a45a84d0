//! The schema a Foxglove channel of shroud declares: the `foxglove` crate's,
//! but with JSON views named `shroud.<View>` rather than by their Rust path
//! (which the crate uses and which would change with any module move), in
//! the bridge and in recordings alike.

use foxglove::{Encode, Schema};

/// `T`'s schema, JSON schemas renamed `shroud.<type>`.
pub fn schema_of<T: Encode>() -> Option<Schema> {
    let mut schema = T::get_schema()?;
    if schema.encoding == "jsonschema" {
        let short = schema.name.rsplit("::").next().unwrap_or_default();
        schema.name = format!("shroud.{short}");
    }
    Some(schema)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::to_foxglove::StatusView;
    use foxglove::messages::PointCloud;

    #[test]
    fn json_views_are_named_by_shroud_and_foxglove_schemas_keep_theirs() {
        let status = schema_of::<StatusView>().unwrap();
        assert_eq!(
            (status.name.as_str(), status.encoding.as_str()),
            ("shroud.StatusView", "jsonschema")
        );
        let cloud = schema_of::<PointCloud>().unwrap();
        assert_eq!(
            (cloud.name.as_str(), cloud.encoding.as_str()),
            ("foxglove.PointCloud", "protobuf")
        );
    }
}
