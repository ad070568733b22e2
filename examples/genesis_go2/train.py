"""Trains the Go2 on rse stepfield tiles in Genesis (go2_stepfield.py) with
rsl-rl's PPO, at the settings of Genesis's Go2 example:

    python examples/genesis_go2/train.py -B 4096 --max_iterations 101
    python examples/genesis_go2/train.py --device cpu -B 4 --max_iterations 1

Needs ``genesis-world`` and ``rsl-rl-lib>=5`` (docs/train.md).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import genesis as gs
from rsl_rl.runners import OnPolicyRunner

sys.path.insert(0, str(Path(__file__).resolve().parent))
from go2_stepfield import Go2Stepfield, make_tiles  # noqa: E402


def ppo_cfg(run_name: str) -> dict:
    """rsl-rl's runner settings of Genesis's Go2 example."""
    mlp = {"class_name": "MLPModel", "hidden_dims": [512, 256, 128], "activation": "elu"}
    return {
        "algorithm": {
            "class_name": "PPO",
            "clip_param": 0.2,
            "desired_kl": 0.01,
            "entropy_coef": 0.01,
            "gamma": 0.99,
            "lam": 0.95,
            "learning_rate": 0.001,
            "max_grad_norm": 1.0,
            "num_learning_epochs": 5,
            "num_mini_batches": 4,
            "schedule": "adaptive",
            "use_clipped_value_loss": True,
            "value_loss_coef": 1.0,
        },
        "actor": {**mlp, "distribution_cfg": {"class_name": "GaussianDistribution", "init_std": 1.0, "std_type": "scalar"}},
        "critic": mlp,
        "obs_groups": {"actor": ["policy"], "critic": ["policy"]},
        "num_steps_per_env": 24,
        "save_interval": 100,
        "run_name": run_name,
        "logger": "tensorboard",
    }


def main(argv: list[str] | None = None) -> Path:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-e", "--exp_name", default="go2-stepfield")
    parser.add_argument("-B", "--num_envs", type=int, default=4096)
    parser.add_argument("--max_iterations", type=int, default=101)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--scheme", default=None, help="an rse scheme file (default: go2_stepfield.STEPFIELD)")
    parser.add_argument("--device", choices=("gpu", "cpu"), default="gpu")
    parser.add_argument("--log_dir", default=None, help="default: logs/<exp_name>")
    args = parser.parse_args(argv)

    log_dir = Path(args.log_dir or f"logs/{args.exp_name}")
    log_dir.mkdir(parents=True, exist_ok=True)
    backend = gs.gpu if args.device == "gpu" else gs.cpu
    gs.init(backend=backend, precision="32", logging_level="warning", seed=args.seed, performance_mode=True)
    env = Go2Stepfield(make_tiles(args.num_envs, args.scheme, seed=args.seed))
    runner = OnPolicyRunner(env, ppo_cfg(args.exp_name), str(log_dir), device=gs.device)
    runner.learn(num_learning_iterations=args.max_iterations, init_at_random_ep_len=True)
    return log_dir


if __name__ == "__main__":
    main()
