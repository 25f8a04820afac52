//! Which Smith masking–shadowing function a microfacet lobe uses ([`super::microfacet`]).

/// Which Smith masking–shadowing function G(wo, wi) a microfacet lobe uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Smith {
    /// 1/(1 + Λ(wo) + Λ(wi)) (Heitz 2014, "Understanding the Masking-Shadowing Function",
    /// §6): heights of masking and shadowing correlated, spectrace's own.
    #[default]
    HeightCorrelated,
    /// G1(wo)·G1(wi), as Mitsuba 3 defines it (`MicrofacetDistribution::G`), for its scenes:
    /// up to a few per cent darker at grazing angles.
    Separable,
}
