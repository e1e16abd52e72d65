#!/usr/bin/env python3
"""A numpy-only learner: the cross-entropy method on a linear lidar policy learns to lap the
racetrack in tianracer_gym. Writes learning_curve.png (progress along the centreline per
iteration) and learning_lap.png (a bird's-eye view of the best policy's lap).

    source .build/devel/setup.bash
    python3 examples/gym_cem.py [--iterations 25] [--population 24] [--out output/learning]

The policy sees the scan as the nearest return in 9 sectors of the 270 degree field of view
(clipped to 3 m) and drives through the cmd_vel node's Ackermann maths:
    speed = 0.6 + 1.4 (1 + tanh(w_v . f)) / 2  (m/s),   steering = 0.5 tanh(w_s . f)  (rad)
with f = (sectors / 3 m, 1): 20 parameters. Each iteration samples a population of parameter
vectors around the mean, runs them side by side in a vector env (C++ threads) from the start
line, keeps the best fifth by progress (m along the centreline before a collision or the time
limit) and moves the mean and spread to them.
"""
import argparse
import os
import time

import numpy as np

import tianracer_gym

SECTORS = 9
FEATURES = SECTORS + 1
START = (0.0, 0.0, 0.0)  # the start line, facing along the track


def features(scan):
    """Nearest return per sector (NaN-free: -inf means too close, +inf nothing in range)."""
    r = np.nan_to_num(np.asarray(scan, np.float64), nan=3.0, posinf=3.0, neginf=0.0)
    r = np.clip(r, 0.0, 3.0)
    sectors = np.array_split(r, SECTORS)
    f = np.empty(FEATURES)
    f[:SECTORS] = [s.min() / 3.0 for s in sectors]
    f[SECTORS] = 1.0
    return f


def act(theta, f):
    w = theta.reshape(2, FEATURES)
    return np.array([0.6 + 0.7 * (1.0 + np.tanh(w[0] @ f)), 0.5 * np.tanh(w[1] @ f)], np.float32)


def evaluate(envs, thetas, episode_time, record=False):
    """Progress (m) of each parameter vector over one episode from the start line; with
    record, also the (x, y, speed) path of each."""
    n = len(thetas)
    obs, _ = envs.reset(seed=0, options={'pose': START})
    done = np.zeros(n, bool)
    progress = np.zeros(n)
    paths = [[] for _ in range(n)]
    while not done.all():
        actions = np.stack([act(thetas[i], features(obs['scan'][i])) for i in range(n)])
        obs, rewards, terminated, truncated, info = envs.step(actions)
        live = ~done
        progress[live] += rewards[live]
        if record:
            for i in np.flatnonzero(live):
                paths[i].append((obs['odom'][i][0], obs['odom'][i][1], obs['odom'][i][7]))
        done |= terminated | truncated
    return progress, paths


def plot_curve(history, lap, path):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    it = np.arange(1, len(history) + 1)
    best = [h[0] for h in history]
    elite = [h[1] for h in history]
    mean = [h[2] for h in history]
    fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=100)
    ax.plot(it, best, 'o-', label='best of the population')
    ax.plot(it, elite, 's-', label='mean of the elite')
    ax.plot(it, mean, '.-', label='mean of the population')
    ax.axhline(lap, color='grey', ls='--', lw=1, label='one lap (%.2f m)' % lap)
    ax.set_xlabel('iteration')
    ax.set_ylabel('progress along the centreline (m)')
    ax.set_title('Cross-entropy method, linear lidar policy, racetrack')
    ax.grid(alpha=0.3)
    ax.legend(loc='lower right', fontsize=8)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def plot_lap(centreline, track, path_xyv, progress, path):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    pts = np.array(track)
    closed = np.vstack([pts, pts[:1]])
    d = np.diff(closed, axis=0)
    n = np.stack([-d[:, 1], d[:, 0]], axis=1)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=100)
    for side in (0.5, -0.5):  # the walls' faces: the centreline +-0.5 m
        w = pts + side * n
        ax.plot(np.append(w[:, 0], w[0, 0]), np.append(w[:, 1], w[0, 1]), color='firebrick', lw=2)
    ax.plot(closed[:, 0], closed[:, 1], color='grey', ls=':', lw=1)
    p = np.array(path_xyv)
    sc = ax.scatter(p[:, 0], p[:, 1], c=p[:, 2], cmap='viridis', s=4)
    fig.colorbar(sc, ax=ax, label='speed (m/s)')
    ax.plot(*START[:2], 'k>', ms=8)
    ax.set_aspect('equal')
    ax.set_title('best policy: %.2f m in one episode (lap %.2f m)' % (progress, centreline.length))
    ax.set_xlabel('x (m)')
    ax.set_ylabel('y (m)')
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--iterations', type=int, default=25)
    p.add_argument('--population', type=int, default=24)
    p.add_argument('--elite', type=float, default=0.2, help='fraction kept')
    p.add_argument('--episode-time', type=float, default=20.0, help='s of sim time')
    p.add_argument('--threads', type=int, default=0, help='0: one per core')
    p.add_argument('--seed', type=int, default=0)
    p.add_argument('--out', default='output/learning')
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)

    rng = np.random.default_rng(args.seed)
    # 40 Hz control: the lidar's rate (the scan is held between its samples).
    envs = tianracer_gym.TianracerVectorEnv(
        args.population, threads=args.threads, observe=('scan', 'odom'), control_period=0.025,
        max_episode_time=args.episode_time, random_start=False)
    centreline = envs.envs[0].centreline
    dim = 2 * FEATURES
    mean, std = np.zeros(dim), np.full(dim, 1.0)
    n_elite = max(2, int(round(args.elite * args.population)))
    history, best_theta, best_score = [], mean.copy(), -np.inf
    cpu0, wall0 = time.process_time(), time.perf_counter()
    for it in range(args.iterations):
        thetas = mean + std * rng.standard_normal((args.population, dim))
        thetas[0] = mean  # the current mean is always one of them
        scores, _ = evaluate(envs, thetas, args.episode_time)
        order = np.argsort(scores)[::-1]
        elite = thetas[order[:n_elite]]
        mean = elite.mean(axis=0)
        std = elite.std(axis=0) + 0.02
        if scores[order[0]] > best_score:
            best_score, best_theta = scores[order[0]], thetas[order[0]].copy()
        history.append((scores[order[0]], scores[order[:n_elite]].mean(), scores.mean()))
        print('iteration %2d: best %6.2f m, elite %6.2f m, population %6.2f m  (%.0f s CPU)' % (
            it + 1, *history[-1], time.process_time() - cpu0), flush=True)

    plot_curve(history, centreline.length, os.path.join(args.out, 'learning_curve.png'))
    progress, paths = evaluate(envs, np.stack([best_theta] * args.population),
                               args.episode_time, record=True)
    from tianracer_bringup.track import centreline as track_points
    plot_lap(centreline, track_points(0.05), paths[0], progress[0],
             os.path.join(args.out, 'learning_lap.png'))
    np.save(os.path.join(args.out, 'best_policy.npy'), best_theta)
    print('best policy: %.2f m (a lap is %.2f m); %d iterations in %.0f s CPU, %.0f s wall; '
          'pictures in %s' % (progress[0], centreline.length, args.iterations,
                              time.process_time() - cpu0, time.perf_counter() - wall0, args.out))
    envs.close()


if __name__ == '__main__':
    main()
