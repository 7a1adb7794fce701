//! `polbrdf_tasks::lut`: the conventions file and the sidecar.

use polbrdf_tasks::lut::{columns, CONVENTIONS};

#[test]
fn the_conventions_are_a_json_object_pinning_the_frame() {
    let v: serde_json::Value = serde_json::from_str(CONVENTIONS).unwrap();
    let o = v.as_object().unwrap();
    assert!(o.contains_key("title") && o.contains_key("model"), "{o:?}");
}

#[test]
fn columns_follow_the_quantities_in_order() {
    use polbrdf_io::lut::Quantity;
    let c = columns(&[Quantity::Dolp, Quantity::Mueller, Quantity::Aolp]);
    assert_eq!(c.len(), 18);
    assert_eq!(
        (c[0].as_str(), c[1].as_str(), c[16].as_str(), c[17].as_str()),
        ("dolp", "m00", "m33", "aolp_deg")
    );
}
