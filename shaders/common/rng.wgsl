// Counter-based randomness, mirrored exactly by crates/perturb/src/rng.rs.
// A draw is pcg4d(counter ^ key): `key` is derived on the CPU from (seed, perturbation, frame,
// purpose) and passed in a uniform; `counter` names the draw (x, y, channel or index, round).
// PCG4D: Jarzynski & Olano 2020, "Hash Functions for GPU Rendering", JCGT 9(3).

fn pcg4d(input: vec4<u32>) -> vec4<u32> {
    var v = input * 1664525u + 1013904223u;
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    v ^= v >> vec4<u32>(16u);
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    return v;
}

fn rng_draw(key: vec4<u32>, counter: vec4<u32>) -> vec4<u32> {
    return pcg4d(counter ^ key);
}

// Uniform in [0, 1): the top 24 bits.
fn rng_uniform(bits: u32) -> f32 {
    return f32(bits >> 8u) * (1.0 / 16777216.0);
}

// Uniform in (0, 1], safe for log.
fn rng_uniform_open(bits: u32) -> f32 {
    return f32((bits >> 8u) + 1u) * (1.0 / 16777216.0);
}

// Two independent standard normals from two uniform words (Box-Muller).
fn rng_normal_pair(a: u32, b: u32) -> vec2<f32> {
    let r = sqrt(-2.0 * log(rng_uniform_open(a)));
    let theta = 6.2831855 * rng_uniform(b);
    return vec2<f32>(r * cos(theta), r * sin(theta));
}

// Three standard normals (one per colour channel) from one draw.
fn rng_normal3(key: vec4<u32>, counter: vec4<u32>) -> vec3<f32> {
    let u = rng_draw(key, counter);
    let n01 = rng_normal_pair(u.x, u.y);
    let n2 = rng_normal_pair(u.z, u.w);
    return vec3<f32>(n01.x, n01.y, n2.x);
}

// ln Γ(x) for x ≥ 1: Stirling series at x + n ≥ 7, shifted down by the recurrence
// (numpy's random_loggam, truncated to the terms that matter in f32).
fn log_gamma(x: f32) -> f32 {
    if (x == 1.0 || x == 2.0) {
        return 0.0;
    }
    var x0 = x;
    var product = 1.0;
    while (x0 < 7.0) {
        product *= x0;
        x0 += 1.0;
    }
    let x2 = 1.0 / (x0 * x0);
    let series = (0.083333333 + x2 * (-0.0027777778 + x2 * 0.00079365079)) / x0;
    return series + 0.91893853 + (x0 - 0.5) * log(x0) - x0 - log(product);
}

// An exact Poisson(lambda) sample for the site (x, y, channel); the round goes in counter.w.
// lambda < 10: inversion by sequential search (one uniform); lambda >= 10: Hörmann's PTRS
// transformed rejection (1993), as numpy's random_poisson. Neither approximates the law.
fn rng_poisson(key: vec4<u32>, site: vec3<u32>, lambda: f32) -> f32 {
    if (lambda <= 0.0) {
        return 0.0;
    }
    if (lambda < 10.0) {
        let u = rng_uniform(rng_draw(key, vec4<u32>(site, 0u)).x);
        var p = exp(-lambda);
        var cdf = p;
        var k = 0.0;
        while (u > cdf && k < 64.0) {
            k += 1.0;
            p *= lambda / k;
            cdf += p;
        }
        return k;
    }
    let slam = sqrt(lambda);
    let loglam = log(lambda);
    let b = 0.931 + 2.53 * slam;
    let a = -0.059 + 0.02483 * b;
    let invalpha = 1.1239 + 1.1328 / (b - 3.4);
    let vr = 0.9277 - 3.6224 / (b - 2.0);
    for (var round = 0u; round < 64u; round++) {
        let w = rng_draw(key, vec4<u32>(site, round));
        // u in (-0.5, 0.5) so that us > 0; v in (0, 1] so that log(v) is finite.
        let u = (f32(w.x >> 8u) + 0.5) * (1.0 / 16777216.0) - 0.5;
        let v = rng_uniform_open(w.y);
        let us = 0.5 - abs(u);
        let k = floor((2.0 * a / us + b) * u + lambda + 0.43);
        if (us >= 0.07 && v <= vr) {
            return k;
        }
        if (k < 0.0 || (us < 0.013 && v > us)) {
            continue;
        }
        if (log(v) + log(invalpha) - log(a / (us * us) + b) <= -lambda + k * loglam - log_gamma(k + 1.0)) {
            return k;
        }
    }
    // 64 rejections in a row have probability below 1e-60.
    return floor(lambda);
}
