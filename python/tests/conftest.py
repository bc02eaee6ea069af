"""Shared fixtures: the datasets folder, the CLI, toy clips and a toy model."""
import os
import pathlib
import subprocess

import pytest

import actionstring

ROOT = pathlib.Path(__file__).resolve().parents[2]


def data_dir() -> pathlib.Path:
    return pathlib.Path(os.environ.get("ACTIONSTRING_DATA", ROOT.parent / "shared" / "data"))


@pytest.fixture(scope="session")
def hdm05() -> pathlib.Path:
    folder = data_dir() / "hdm05"
    if not (folder / "train.tsv").is_file():
        pytest.skip(f"HDM05 data absent: {folder}/train.tsv not found (set ACTIONSTRING_DATA)")
    return folder


@pytest.fixture(scope="session")
def msr() -> pathlib.Path:
    folder = data_dir() / "msr-action3d"
    if not (folder / "train.tsv").is_file():
        pytest.skip(f"MSR Action3D data absent: {folder}/train.tsv not found (set ACTIONSTRING_DATA)")
    return folder


@pytest.fixture(scope="session")
def cli() -> str:
    path = os.environ.get("ACTIONSTRING_CLI")
    if not path or not os.access(path, os.X_OK):
        pytest.skip("ACTIONSTRING_CLI is not set to the actionstring executable (CTest sets it)")
    return path


def run_cli(cli: str, *args: str) -> str:
    done = subprocess.run([cli, *map(str, args)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout


@pytest.fixture(scope="session")
def toy_clips():
    """Synthetic clips of the toy world: 4 actions by 6 'subjects' (toy0..toy5)."""
    return actionstring._native._toy_clips(6, 11)


TOY_SETTINGS = dict(components=0, pca=8, string_rate=10, sigma=4.0, keep_singletons=True)


@pytest.fixture(scope="session")
def toy_model(toy_clips):
    return actionstring.train(toy_clips, **TOY_SETTINGS)
