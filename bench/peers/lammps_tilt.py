#!/usr/bin/python3
"""Peer comparison: the tilting-block test in LAMMPS (Debian `lammps`, 7 Jan 2022, binary `lmp`).

Debian's LAMMPS `pair_style body/rounded/polygon` cannot hold static friction (no tangential
history), so each block face is a chain of overlapping disks (atom_style sphere, 2d) with
`pair_style gran/hooke/history`; each block is one rigid set of disks:
  lower block: `fix move rotate` about (0, -h/2) (the centre of the Table I lower block),
               clockwise at 0.05 rad/s after a 0.1 s settle (upper block slides towards +x);
  upper block: `fix rigid/nve single` under `fix gravity`.
Disk centres sit on the profile (so each face is the profile offset by the disk radius r, the
analogue of frictal's spheroradius). The two chains use incommensurate spacings (upper = 1.3x
lower, rounded per segment) so that the disk-scale bumps average out rather than interlock.
Contact law per disk pair (LAMMPS hooke): F_n = k_n delta - m_eff gamma_n v_n,
F_t = -k_t xi - m_eff gamma_t v_t, |F_t| <= mu_a F_n, with the Table II values k_n = 6e5 N/m,
k_t = 6e4 N/m, gamma_n = 929.5 1/s, gamma_t = 4 1/s, mu_a from the case; m_eff = upper block
mass (lower disks are given a huge mass; LAMMPS uses the rigid-body mass for fix rigid atoms).
Detection rule as frictal (docs/dem.md): d = upper-centre displacement in the lower block frame,
v = dd/dt (from the centre-of-mass velocity and the lower block's rotation), stick = >= 20 ms at
v <= 1e-5 m/s, friction angle = tilt at the end of the last stick before d grows by lambda.
  usage: lammps_tilt.py flat MU | lammps_tilt.py k0 ALPHA_DEG MU   [--r R] [--s S] [--ratio Q] [--dt DT]
prints one JSON line.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

p = argparse.ArgumentParser()
p.add_argument('kind', choices=['flat', 'k0'])
p.add_argument('args', nargs='+', type=float)
p.add_argument('--r', type=float, default=5e-4, help='disk radius, m')
p.add_argument('--s', type=float, default=5e-4, help='lower chain spacing, m (upper: 1.3x)')
p.add_argument('--ratio', type=float, default=1.3, help='upper/lower chain spacing (1 = commensurate)')
p.add_argument('--dt', type=float, default=2e-5)
p.add_argument('--lmp', default='lmp')
p.add_argument('--keep', default='', help='directory to keep the input/log in')
p.add_argument('--parse-only', action='store_true', help='re-read --keep/log.lammps')
a = p.parse_args()
k0 = a.kind == 'k0'
alpha = math.radians(a.args[0]) if k0 else 0.0
mu = a.args[1] if k0 else a.args[0]
L, lam, h = 0.2, 0.01, 0.01
rate, settle, dt, r = 0.05, 0.1, a.dt, a.r
mass_upper = 50 * L * h  # Table II rho x L_b x h (chain of disks carries the block's mass)
expected = math.degrees(alpha + math.atan(mu))


def chain(vertices, spacing):
    """Disk centres along a polyline, vertices included, each segment split evenly."""
    pts = [vertices[0]]
    for (x0, y0), (x1, y1) in zip(vertices, vertices[1:]):
        seg = math.hypot(x1 - x0, y1 - y0)
        n = max(1, round(seg / spacing))
        pts += [(x0 + (x1 - x0) * k / n, y0 + (y1 - y0) * k / n) for k in range(1, n + 1)]
    return pts


teeth = round(L / lam)
th = 0.5 * lam * math.tan(alpha)
if k0:  # triangle wave, teeth up, valleys at -L/2 + i lam
    prof = [(-L / 2 + i * lam / 2, th if i % 2 else 0.0) for i in range(2 * teeth + 1)]
else:
    prof = [(-L / 2, 0.0), (L / 2, 0.0)]
lower = chain(prof, a.s)
lift = 2 * r / math.cos(alpha) + 1e-6  # nested, flanks 1 um apart
upper = [(x, y + lift) for x, y in chain(prof, a.ratio * a.s)]

work = a.keep or tempfile.mkdtemp(prefix='lammps_tilt_')
os.makedirs(work, exist_ok=True)
with open(os.path.join(work, 'blocks.data'), 'w') as f:
    f.write('frictal tilt: lower (type 1), upper (type 2) disk chains\n\n')
    f.write(f'{len(lower) + len(upper)} atoms\n2 atom types\n\n')
    f.write('-0.3 0.3 xlo xhi\n-0.3 0.3 ylo yhi\n-0.001 0.001 zlo zhi\n\nAtoms # sphere\n\n')
    # atom-ID atom-type diameter density x y z ; density set below with `set ... mass`
    for i, (x, y) in enumerate(lower + upper, 1):
        f.write(f'{i} {1 if i <= len(lower) else 2} {2 * r:.9g} 1 {x:.12g} {y:.12g} 0\n')

out_every = max(1, round(1e-3 / dt))  # 1 ms samples for the detection rule
max_tilt = math.radians(expected + 12)
tilt_steps = round(max_tilt / rate / dt)
px, py = 0.0, -h / 2
inp = f"""
units si
dimension 2
boundary f f p
atom_style sphere
atom_modify map array
comm_modify vel yes
read_data blocks.data
group lower type 1
group upper type 2
set group lower mass 1e6
set group upper mass {mass_upper / len(upper):.12g}
pair_style gran/hooke/history 6e5 6e4 929.5 4 {mu} 1
pair_coeff * *
neighbor {0.4 * r:.6g} bin
neigh_modify delay 0 every 1 check yes exclude type 1 1 exclude type 2 2
timestep {dt}
fix grav upper gravity 9.81 vector 0 -1 0
fix body upper rigid/nve single
variable xu equal xcm(upper,x)
variable yu equal xcm(upper,y)
variable vxu equal vcm(upper,x)
variable vyu equal vcm(upper,y)
thermo_style custom step v_xu v_yu v_vxu v_vyu
thermo_modify norm no lost ignore format float %.12g
thermo {out_every}
run {round(settle / dt)}
variable phi equal -{rate}*(time-{settle})
variable dloc equal cos(v_phi)*(v_xu-({px}))+sin(v_phi)*(v_yu-({py}))
variable d0 equal $(v_dloc:%.12g)
variable gone equal v_dloc-v_d0
fix rot lower move rotate {px} {py} 0 0 0 -1 {2 * math.pi / rate:.12g}
fix stop all halt {out_every} v_gone > {1.5 * lam} error continue
run {tilt_steps}
"""
with open(os.path.join(work, 'in.tilt'), 'w') as f:
    f.write(inp)
t0 = time.monotonic()
res = subprocess.CompletedProcess([], 0) if a.parse_only else subprocess.run([a.lmp, '-in', 'in.tilt', '-log', 'log.lammps', '-screen', 'none'], cwd=work,
                     capture_output=True, text=True)
wall = time.monotonic() - t0
if res.returncode != 0:
    sys.stderr.write(res.stdout + res.stderr)
    sys.exit(f'lmp failed, see {work}/log.lammps')

lmp_loop = 0.0  # LAMMPS' own 'Loop time' (excludes start-up and input parsing)
rows = []
with open(os.path.join(work, 'log.lammps')) as f:
    header = False
    for line in f:
        w = line.split()
        if line.startswith('Loop time of'):
            lmp_loop += float(w[3])
        if w[:2] == ['Step', 'v_xu']:
            header = True
            continue
        if header:
            try:
                rows.append([float(x) for x in w])
            except ValueError:
                header = False
# detection (frictal's rule), from the start of the tilt
vs, stick_dur = 1e-5, 0.02
d0 = None
low_since, stick_tilt, stick_d, phi = settle, 0.0, 0.0, None
last_step = 0
for step, x, y, vx, vy in rows:
    t = step * dt
    last_step = int(step)
    if t < settle - 1e-12:
        continue
    ang = -rate * (t - settle)  # lower block angle (clockwise)
    c, s_ = math.cos(ang), math.sin(ang)
    d = c * (x - px) + s_ * (y - py)
    v = c * vx + s_ * vy - rate * (-s_ * (x - px) + c * (y - py))
    if d0 is None:
        d0 = d
    d -= d0
    if v <= vs:
        if low_since is None:
            low_since = t
        if t - low_since >= stick_dur:
            stick_tilt, stick_d = rate * (t - settle), d
    else:
        low_since = None
    if d - stick_d >= lam:
        phi = math.degrees(stick_tilt)
        break
sim = last_step * dt
print(json.dumps({'peer': 'lammps-20220106', 'case': a.kind, 'alpha_deg': math.degrees(alpha), 'mu': mu,
                  'friction_angle_deg': None if phi is None else round(phi, 4),
                  'expected_deg': round(expected, 4), 'disks': [len(lower), len(upper)], 'r_m': r,
                  'spacing_m': [a.s, round(a.ratio * a.s, 9)], 'steps': last_step, 'dt_s': dt, 'simulated_time_s': round(sim, 4),
                  'wall_time_s': round(wall, 3), 'lammps_loop_time_s': round(lmp_loop, 3),
                  'wall_s_per_sim_s': round(lmp_loop / sim, 3),
                  'us_per_step': round(1e6 * lmp_loop / max(1, last_step), 3)}))
