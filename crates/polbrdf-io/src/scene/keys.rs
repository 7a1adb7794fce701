//! The key table of scene files: every key and table with its kind and what it holds, the
//! [`TomlDoc`](crate::toml_doc::TomlDoc) format that checks a file against it.

use crate::toml_doc::{key, Format, Key, Kind};

/// Every key and table of a scene file, tables before their keys.
pub(super) const KEYS: &[Key] = &[
    key("wavelength_um", Kind::Number, "one wavelength, µm"),
    key(
        "band",
        Kind::Table,
        "a band: [band] with response = \"FILE.csv\"",
    ),
    key(
        "band.response",
        Kind::Text,
        "the path of a band CSV file with columns wavelength_um,response",
    ),
    key("band.step_um", Kind::Number, "the quadrature step, µm"),
    key("surface", Kind::Table, "the surface of `polbrdf radiance`"),
    key(
        "surface.temperature_k",
        Kind::Number,
        "the surface temperature, K",
    ),
    key("target", Kind::Table, "the target of `polbrdf contrast`"),
    key(
        "target.material",
        Kind::Text,
        "a material file or a preset name",
    ),
    key("target.temperature_k", Kind::Number, "a temperature, K"),
    key(
        "background",
        Kind::Table,
        "the background of `polbrdf contrast`",
    ),
    key(
        "background.material",
        Kind::Text,
        "a material file or a preset name",
    ),
    key("background.temperature_k", Kind::Number, "a temperature, K"),
    key(
        "sun",
        Kind::Table,
        "the sun: [sun] with irradiance, and zenith_deg or date_time with latitude_deg and \
         longitude_deg",
    ),
    key(
        "sun.zenith_deg",
        Kind::Number,
        "the sun's zenith angle, degrees, in [0, 90)",
    ),
    key(
        "sun.azimuth_deg",
        Kind::Number,
        "the sun's azimuth, degrees",
    ),
    key(
        "sun.date_time",
        Kind::DateTime,
        "the date and time with its UTC offset, e.g. 2026-06-21T12:00:00Z",
    ),
    key(
        "sun.latitude_deg",
        Kind::Number,
        "the latitude, degrees, in [-90, 90] (north positive)",
    ),
    key(
        "sun.longitude_deg",
        Kind::Number,
        "the longitude, degrees, in [-180, 180] (east positive)",
    ),
    key(
        "sun.elevation_m",
        Kind::Number,
        "the height above sea level, m",
    ),
    key(
        "sun.pressure_hpa",
        Kind::Number,
        "the air pressure for refraction, hPa (0: no refraction)",
    ),
    key(
        "sun.temperature_c",
        Kind::Number,
        "the air temperature for refraction, °C",
    ),
    key(
        "sun.delta_t_s",
        Kind::Number,
        "ΔT = TT − UT1, s (default: estimated from the date)",
    ),
    key(
        "sun.phi0_azimuth_deg",
        Kind::Number,
        "the compass azimuth (from north toward east) of the surface's φ = 0 axis, degrees",
    ),
    key(
        "sun.irradiance",
        Kind::Number,
        "the sun's spectral irradiance on a plane normal to its beam, W·m⁻²·µm⁻¹",
    ),
    key(
        "sun.stokes",
        Kind::Numbers,
        "the sun's Stokes vector [s0, s1, s2, s3]",
    ),
    key("sky", Kind::Table, "the sky"),
    key("sky.model", Kind::Text, "a sky model"),
    key(
        "sky.radiance",
        Kind::Number,
        "the uniform sky's spectral radiance, W·m⁻²·sr⁻¹·µm⁻¹",
    ),
    key(
        "sky.temperature_k",
        Kind::Number,
        "the sky's brightness temperature, K",
    ),
    key(
        "sky.file",
        Kind::Text,
        "the path of a CSV file: a sky profile with columns zenith_deg,radiance, or a sky table \
         with columns theta_deg,phi_deg,s0,s1,s2,s3",
    ),
    key(
        "sky.irradiance",
        Kind::Number,
        "the clear sky's horizontal spectral irradiance, W·m⁻²·µm⁻¹",
    ),
    key(
        "sky.dop_max",
        Kind::Number,
        "the clear sky's maximum degree of polarization, in [0, 1]",
    ),
    key(
        "atmosphere",
        Kind::Table,
        "the atmosphere between surface and sensor",
    ),
    key(
        "atmosphere.transmittance",
        Kind::Number,
        "the transmittance, in [0, 1]",
    ),
    key(
        "atmosphere.path_radiance",
        Kind::Number,
        "the path spectral radiance, W·m⁻²·sr⁻¹·µm⁻¹",
    ),
    key(
        "path",
        Kind::Table,
        "the path to a detecting sensor (`polbrdf detect`)",
    ),
    key(
        "path.extinction_per_m",
        Kind::Number,
        "the extinction coefficient, m⁻¹",
    ),
    key(
        "path.visibility_km",
        Kind::Number,
        "the meteorological visibility, km (Koschmieder: β = 3.912/V)",
    ),
    key(
        "path.horizon_radiance",
        Kind::Number,
        "the horizon spectral radiance, W·m⁻²·sr⁻¹·µm⁻¹",
    ),
    key(
        "path.air_temperature_k",
        Kind::Number,
        "the air temperature, K (horizon radiance B(T_air))",
    ),
    key(
        "path.table",
        Kind::Text,
        "the path of a CSV file with columns range_m,transmittance,path_radiance",
    ),
];

/// Every key and table of a scene file by its dotted name (`table.key` inside a table), tables
/// before their keys, in the order of the format's description.
pub fn key_names() -> impl Iterator<Item = &'static str> {
    KEYS.iter().map(|k| k.name)
}

/// The scene format of [`TomlDoc`](crate::toml_doc::TomlDoc).
pub(super) const FORMAT: Format<'static> = Format {
    noun: "scene file",
    example: "`wavelength_um = 10`",
    keys: KEYS,
};
