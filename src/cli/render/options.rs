//! The render options of `spectrace render`: the library API's, resolved from the command line
//! and the scene, plus what only the CLI has (a bdpt strategy, a farm part).

use super::*;

/// The render options from the command line and the scene, checked: the integrator's strategy,
/// spectral bins for a camera sensor's curves, a farm part.
pub(super) fn options(
    args: &RenderArgs,
    api_scene: &crate::api::Scene,
) -> Result<RenderOptions, CliError> {
    // the library API resolves and checks the options, as for every user of it
    let api_opts = api_options(args)?;
    let mut opts = api_opts.render_options(api_scene).map_err(|e| match e {
        // "spectral_bins must be …" → "--spectral-bins must be …"
        crate::api::Error::Options(m) => CliError::Usage(format!("--{}", m.replacen('_', "-", 1))),
        other => CliError::Usage(other.to_string()),
    })?;
    let scene = api_scene.inner();
    opts.strategy = bdpt_strategy(args, &opts)?;
    if let Some(d) = &args.dispersion {
        opts.split_dispersion = d == "split";
    }
    let splats = matches!(
        opts.integrator,
        IntegratorKind::Light | IntegratorKind::Bdpt
    );
    if scene.integrator.moment && splats {
        // light paths splat into many pixels: a per-pixel second moment of samples is not
        // defined for them
        eprintln!(
            "note: light tracing and bdpt write no second moments (m2.*); the scene's moment integrator applies to camera-ray integrators"
        );
    }
    // a camera's sensitivities are integrated over spectral bins: 5 nm unless asked otherwise
    if scene
        .camera_sensor
        .as_ref()
        .is_some_and(|s| s.curves.is_some())
        && opts.spectral_bins == 0
    {
        opts.spectral_bins = (scene.wavelengths.width() / 5.0).ceil().max(1.0) as u32;
        if !args.quiet {
            eprintln!(
                "note: the camera sensor's curves are integrated over {} spectral bins of 5 nm, which the EXR also holds",
                opts.spectral_bins
            );
        }
    }
    let budgets = args.time.is_some() || args.target_error.is_some();
    if let Some(p) = &args.part {
        if budgets {
            return Err(CliError::Usage(
                "--part renders a fixed share of the samples; it cannot be combined with --time or --target-error".into(),
            ));
        }
        opts.part = Some(crate::cli::farm::parse_part(p, opts.spp)?);
    }
    Ok(opts)
}

/// The library API's options from the command line (the API checks their ranges).
fn api_options(args: &RenderArgs) -> Result<crate::api::Options, CliError> {
    Ok(crate::api::Options {
        spp: args.spp,
        seed: args.seed,
        threads: args.threads,
        integrator: match args.integrator.as_deref() {
            None => None,
            Some(name) => Some(IntegratorKind::from_name(name).ok_or_else(|| {
                CliError::Usage(format!(
                    "--integrator {name}: expected one of {}",
                    IntegratorKind::NAMES.join(", ")
                ))
            })?),
        },
        spectral_bins: args.spectral_bins,
        time_limit: match &args.time {
            Some(t) => Some(crate::cli::farm::parse_duration(t, "--time")?),
            None => None,
        },
        target_error: args.target_error,
    })
}

/// `--bdpt-strategy S,T` checked against the integrator and the scene's depth (None: not given).
fn bdpt_strategy(
    args: &RenderArgs,
    opts: &crate::render::RenderOptions,
) -> Result<Option<crate::integrator::bdpt::Strategy>, CliError> {
    let Some(st) = &args.bdpt_strategy else {
        return Ok(None);
    };
    let parsed = st
        .split_once(',')
        .and_then(|(a, b)| Some((a.trim().parse::<u32>().ok()?, b.trim().parse::<u32>().ok()?)));
    let Some((s, t)) = parsed else {
        return Err(CliError::Usage(format!(
            "--bdpt-strategy {st}: expected S,T (light and camera vertex counts, e.g. 1,2)"
        )));
    };
    if opts.integrator != IntegratorKind::Bdpt {
        return Err(CliError::Usage(
            "--bdpt-strategy needs the bdpt integrator (--integrator bdpt)".into(),
        ));
    }
    if t == 0 || s.saturating_add(t) < 2 || (s, t) == (1, 1) {
        return Err(CliError::Usage(format!(
            "--bdpt-strategy {s},{t}: bdpt has no such strategy (t ≥ 1, s + t ≥ 2, not 1,1)"
        )));
    }
    if s as u64 + t as u64 - 2 > opts.max_depth as u64 {
        return Err(CliError::Usage(format!(
            "--bdpt-strategy {s},{t}: its paths have {} bounces, more than the scene's max_depth {}",
            s as u64 + t as u64 - 2,
            opts.max_depth
        )));
    }
    Ok(Some(crate::integrator::bdpt::Strategy {
        s,
        t,
        weighted: !args.bdpt_unweighted,
    }))
}
