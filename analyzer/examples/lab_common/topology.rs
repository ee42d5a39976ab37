//! The joints' topology of a structure map: which of its dark pixels form a network, how that
//! network branches (T-junctions of a running bond, crossings of a grid, Y-junctions of
//! irregular stones, free ends of planks and cracks), and the shape of the pieces it closes.
//!
//! Measured on the dark minority of the map after its shading is removed; the bright network
//! is measured on the negated map. Every number is invariant to rotation; the lengths are in
//! units of the pieces' size where they can be, so that scale matters as little as possible.

use proctex::cues::blur;

/// How many numbers [`topology`] returns.
pub const TOPOLOGY: usize = 13;

/// The ring's Chebyshev radius (pixels) at which a junction's branches are counted.
const RING: i64 = 4;

/// The share of the map taken as the candidate network.
const MINORITY: f32 = 0.3;

/// Topology features of an `n × n` map (its dark phase as the network).
pub fn topology(map: &[f32], n: usize) -> [f64; TOPOLOGY] {
    let detrended: Vec<f32> = {
        let shade = blur(map, n, n as f32 / 10.0);
        map.iter().zip(&shade).map(|(a, b)| a - b).collect()
    };
    let mask = if std::env::var("TOPO").as_deref() == Ok("valley") {
        valleys(&detrended, n)
    } else {
        let mut sorted = detrended.clone();
        sorted.sort_by(f32::total_cmp);
        let t = sorted[((sorted.len() - 1) as f32 * MINORITY) as usize];
        detrended.iter().map(|&v| v < t).collect()
    };
    let mut out = [0.0; TOPOLOGY];

    // 1. Connectivity: the network's largest 8-connected component's share of its pixels.
    let (net_labels, net_count) = label(&mask, n, true);
    let mut sizes = vec![0usize; net_count];
    for &l in &net_labels {
        if l != usize::MAX {
            sizes[l] += 1;
        }
    }
    let total = mask.iter().filter(|&&b| b).count().max(1);
    out[0] = *sizes.iter().max().unwrap_or(&0) as f64 / total as f64;

    // 2. Pieces: 4-connected components of the rest; those clear of the border are closed.
    let rest: Vec<bool> = mask.iter().map(|&b| !b).collect();
    let (piece_labels, piece_count) = label(&rest, n, false);
    let mut m = vec![[0.0f64; 6]; piece_count]; // count, Σx, Σy, Σxx, Σyy, Σxy
    let mut touches = vec![false; piece_count];
    for y in 0..n {
        for x in 0..n {
            let l = piece_labels[y * n + x];
            if l == usize::MAX {
                continue;
            }
            let (fx, fy) = (x as f64, y as f64);
            let s = &mut m[l];
            s[0] += 1.0;
            s[1] += fx;
            s[2] += fy;
            s[3] += fx * fx;
            s[4] += fy * fy;
            s[5] += fx * fy;
            if x == 0 || y == 0 || x + 1 == n || y + 1 == n {
                touches[l] = true;
            }
        }
    }
    let rest_area = rest.iter().filter(|&&b| b).count().max(1) as f64;
    let mut closed_area = 0.0;
    let (mut log_aspect, mut fill, mut log_area) = (Vec::new(), Vec::new(), Vec::new());
    for (s, &edge) in m.iter().zip(&touches) {
        if edge || s[0] < 6.0 {
            continue;
        }
        closed_area += s[0];
        let (mx, my) = (s[1] / s[0], s[2] / s[0]);
        let (cxx, cyy, cxy) = (
            s[3] / s[0] - mx * mx + 1.0 / 12.0,
            s[4] / s[0] - my * my + 1.0 / 12.0,
            s[5] / s[0] - mx * my,
        );
        let tr = cxx + cyy;
        let det = (cxx * cyy - cxy * cxy).max(1e-9);
        let disc = (tr * tr / 4.0 - det).max(0.0).sqrt();
        let (l1, l2) = (tr / 2.0 + disc, (tr / 2.0 - disc).max(1e-9));
        log_aspect.push(0.5 * (l1 / l2).ln());
        fill.push(s[0] / (4.0 * std::f64::consts::PI * det.sqrt()));
        log_area.push(s[0].ln());
    }
    out[1] = closed_area / rest_area;
    out[2] = median(&mut log_aspect.clone());
    out[3] = spread(&mut log_aspect);
    out[4] = median(&mut fill);
    out[5] = spread(&mut log_area);

    // 3. The network's skeleton, its spurs pruned; junctions counted on a ring around each.
    let mut skeleton = thin(&mask, n);
    prune(&mut skeleton, n, RING as usize + 1);
    let skeleton_px = skeleton.iter().filter(|&&b| b).count();
    let mut junction = vec![false; n * n];
    let mut ends = 0usize;
    for y in 1..n - 1 {
        for x in 1..n - 1 {
            if !skeleton[y * n + x] {
                continue;
            }
            let (neighbours, crossing) = ring8(&skeleton, n, x, y);
            if neighbours == 1 {
                ends += 1;
            }
            if crossing >= 3 {
                junction[y * n + x] = true;
            }
        }
    }
    let (node_labels, node_count) = label(&junction, n, true);
    let mut centre = vec![(0.0f64, 0.0f64, 0.0f64); node_count];
    for (i, &l) in node_labels.iter().enumerate() {
        if l != usize::MAX {
            centre[l].0 += (i % n) as f64;
            centre[l].1 += (i / n) as f64;
            centre[l].2 += 1.0;
        }
    }
    let (mut threes, mut fours, mut t_like, mut y_like) = (0usize, 0usize, 0usize, 0usize);
    let mut stems = (0.0f64, 0.0f64, 0usize);
    for &(sx, sy, c) in &centre {
        let (cx, cy) = ((sx / c).round() as i64, (sy / c).round() as i64);
        if cx < RING || cy < RING || cx + RING >= n as i64 || cy + RING >= n as i64 {
            continue;
        }
        let angles = branches(&skeleton, n, cx, cy);
        match angles.len() {
            3 => {
                threes += 1;
                let gaps = [
                    angles[1] - angles[0],
                    angles[2] - angles[1],
                    std::f64::consts::TAU - (angles[2] - angles[0]),
                ];
                let widest = (0..3).max_by(|&a, &b| gaps[a].total_cmp(&gaps[b])).unwrap();
                let max_gap = gaps[widest];
                if max_gap > 0.8 * std::f64::consts::PI {
                    t_like += 1;
                    // The stem is the branch opposite the widest gap.
                    let stem = angles[(widest + 2) % 3];
                    stems.0 += (2.0 * stem).cos();
                    stems.1 += (2.0 * stem).sin();
                    stems.2 += 1;
                }
                if max_gap < 0.75 * std::f64::consts::PI {
                    y_like += 1;
                }
            }
            k if k >= 4 => fours += 1,
            _ => {}
        }
    }
    let nodes = (threes + fours).max(1) as f64;
    // Branch length per junction, in units of the pieces' typical size (the square root of
    // the median closed piece's area), so that scale cancels.
    let piece_side = if log_area.is_empty() {
        n as f64
    } else {
        median(&mut log_area.clone()).exp().sqrt()
    };
    out[6] = ((skeleton_px as f64 / nodes) / piece_side).max(0.05).ln();
    out[7] = ends as f64 / (ends as f64 + nodes);
    out[8] = fours as f64 / nodes;
    out[9] = t_like as f64 / threes.max(1) as f64;
    out[10] = y_like as f64 / threes.max(1) as f64;
    out[11] = if stems.2 > 0 {
        (stems.0 * stems.0 + stems.1 * stems.1).sqrt() / stems.2 as f64
    } else {
        0.0
    };

    // 4. The skeleton's orientation: 4-fold coherence of the map's gradient along it.
    let g = blur(&detrended, n, 1.0);
    let (mut c4, mut s4, mut w) = (0.0f64, 0.0f64, 0.0f64);
    for y in 1..n - 1 {
        for x in 1..n - 1 {
            if !skeleton[y * n + x] {
                continue;
            }
            let gx = (g[y * n + x + 1] - g[y * n + x - 1]) as f64;
            let gy = (g[(y + 1) * n + x] - g[(y - 1) * n + x]) as f64;
            let a = gy.atan2(gx);
            let mag = (gx * gx + gy * gy).sqrt();
            c4 += mag * (4.0 * a).cos();
            s4 += mag * (4.0 * a).sin();
            w += mag;
        }
    }
    out[12] = if w > 0.0 {
        (c4 * c4 + s4 * s4).sqrt() / w
    } else {
        0.0
    };
    out
}

fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Interquartile range (0 for fewer than four values).
fn spread(v: &mut [f64]) -> f64 {
    if v.len() < 4 {
        return 0.0;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() * 3 / 4] - v[v.len() / 4]
}

/// Connected components of the `true` pixels (8- or 4-connected, not wrapping): a label per
/// pixel (`usize::MAX` outside) and the count.
pub fn label(mask: &[bool], n: usize, eight: bool) -> (Vec<usize>, usize) {
    let mut labels = vec![usize::MAX; n * n];
    let mut next = 0;
    let mut stack = Vec::new();
    for s in 0..n * n {
        if !mask[s] || labels[s] != usize::MAX {
            continue;
        }
        labels[s] = next;
        stack.push(s);
        while let Some(j) = stack.pop() {
            let (x, y) = ((j % n) as i64, (j / n) as i64);
            for dy in -1i64..=1 {
                for dx in -1i64..=1 {
                    if (dx == 0 && dy == 0) || (!eight && dx != 0 && dy != 0) {
                        continue;
                    }
                    let (nx, ny) = (x + dx, y + dy);
                    if nx < 0 || ny < 0 || nx >= n as i64 || ny >= n as i64 {
                        continue;
                    }
                    let k = ny as usize * n + nx as usize;
                    if mask[k] && labels[k] == usize::MAX {
                        labels[k] = next;
                        stack.push(k);
                    }
                }
            }
        }
        next += 1;
    }
    (labels, next)
}

/// The 8 neighbours of (x, y) in clockwise order from north.
fn neighbourhood(m: &[bool], n: usize, x: usize, y: usize) -> [bool; 8] {
    let at = |dx: i64, dy: i64| m[(y as i64 + dy) as usize * n + (x as i64 + dx) as usize];
    [
        at(0, -1),
        at(1, -1),
        at(1, 0),
        at(1, 1),
        at(0, 1),
        at(-1, 1),
        at(-1, 0),
        at(-1, -1),
    ]
}

/// (neighbour count, crossing number: 0→1 transitions around the ring).
fn ring8(m: &[bool], n: usize, x: usize, y: usize) -> (usize, usize) {
    let p = neighbourhood(m, n, x, y);
    let count = p.iter().filter(|&&b| b).count();
    let crossing = (0..8).filter(|&i| !p[i] && p[(i + 1) % 8]).count();
    (count, crossing)
}

/// Zhang–Suen thinning (the border row and column stay empty).
fn thin(mask: &[bool], n: usize) -> Vec<bool> {
    let mut m = mask.to_vec();
    for i in 0..n {
        m[i] = false;
        m[(n - 1) * n + i] = false;
        m[i * n] = false;
        m[i * n + n - 1] = false;
    }
    loop {
        let mut changed = false;
        for pass in 0..2 {
            let mut remove = Vec::new();
            for y in 1..n - 1 {
                for x in 1..n - 1 {
                    if !m[y * n + x] {
                        continue;
                    }
                    let p = neighbourhood(&m, n, x, y);
                    let b = p.iter().filter(|&&v| v).count();
                    let a = (0..8).filter(|&i| !p[i] && p[(i + 1) % 8]).count();
                    // p[0]=N, p[2]=E, p[4]=S, p[6]=W
                    let (c1, c2) = if pass == 0 {
                        (p[0] && p[2] && p[4], p[2] && p[4] && p[6])
                    } else {
                        (p[0] && p[2] && p[6], p[0] && p[4] && p[6])
                    };
                    if (2..=6).contains(&b) && a == 1 && !c1 && !c2 {
                        remove.push(y * n + x);
                    }
                }
            }
            changed |= !remove.is_empty();
            for i in remove {
                m[i] = false;
            }
        }
        if !changed {
            return m;
        }
    }
}

/// Remove free ends `rounds` times: spurs shorter than that vanish, longer lines lose as much.
fn prune(m: &mut [bool], n: usize, rounds: usize) {
    for _ in 0..rounds {
        let ends: Vec<usize> = (1..n - 1)
            .flat_map(|y| (1..n - 1).map(move |x| (x, y)))
            .filter(|&(x, y)| m[y * n + x] && ring8(m, n, x, y).0 <= 1)
            .map(|(x, y)| y * n + x)
            .collect();
        if ends.is_empty() {
            return;
        }
        for i in ends {
            m[i] = false;
        }
    }
}

/// The directions (radians, ascending in [0, 2π)) of the skeleton's branches crossing the
/// square ring at Chebyshev radius `RING` around (cx, cy): one per run of skeleton pixels.
fn branches(m: &[bool], n: usize, cx: i64, cy: i64) -> Vec<f64> {
    let r = RING;
    let mut ring = Vec::with_capacity(8 * r as usize);
    for i in -r..r {
        ring.push((i, -r));
    }
    for i in -r..r {
        ring.push((r, i));
    }
    for i in -r..r {
        ring.push((-i, r));
    }
    for i in -r..r {
        ring.push((-r, -i));
    }
    let hit: Vec<bool> = ring
        .iter()
        .map(|&(dx, dy)| m[(cy + dy) as usize * n + (cx + dx) as usize])
        .collect();
    let len = hit.len();
    let Some(start) = (0..len).find(|&i| !hit[i]) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let mut run: Vec<(i64, i64)> = Vec::new();
    for k in 1..=len {
        let i = (start + k) % len;
        if hit[i] {
            run.push(ring[i]);
        } else if !run.is_empty() {
            let (sx, sy) = run
                .iter()
                .fold((0.0, 0.0), |(a, b), &(x, y)| (a + x as f64, b + y as f64));
            out.push(sy.atan2(sx).rem_euclid(std::f64::consts::TAU));
            run.clear();
        }
    }
    out.sort_by(f64::total_cmp);
    out
}

/// The map's dark valleys (joints, cracks): where the larger eigenvalue of the Hessian of the
/// map blurred by `VALLEY_SIGMA` is positive and among the top `MINORITY` share. Unlike a
/// threshold on the value, it finds a joint between pieces of any tone.
fn valleys(map: &[f32], n: usize) -> Vec<bool> {
    const VALLEY_SIGMA: f32 = 1.5;
    let b = blur(map, n, VALLEY_SIGMA);
    let at = |x: usize, y: usize| b[(y % n) * n + x % n];
    let mut lambda = vec![0.0f32; n * n];
    for y in 0..n {
        for x in 0..n {
            let (xm, xp, ym, yp) = (x + n - 1, x + 1, y + n - 1, y + 1);
            let c = at(x, y);
            let hxx = at(xp, y) - 2.0 * c + at(xm, y);
            let hyy = at(x, yp) - 2.0 * c + at(x, ym);
            let hxy = (at(xp, yp) - at(xm, yp) - at(xp, ym) + at(xm, ym)) / 4.0;
            let half = (hxx - hyy) / 2.0;
            lambda[y * n + x] = (hxx + hyy) / 2.0 + (half * half + hxy * hxy).sqrt();
        }
    }
    let mut sorted = lambda.clone();
    sorted.sort_by(f32::total_cmp);
    let t = sorted[((sorted.len() - 1) as f32 * (1.0 - MINORITY)) as usize].max(0.0);
    lambda.iter().map(|&l| l > t).collect()
}
