"""A sweep file (TOML) read and checked before any work starts (docs/SWEEPS.md).

Every problem is a SweepFileError naming the file and the key; nothing is run for a bad file.
"""
import dataclasses
import os
import subprocess
import tomllib

from . import _sweep_tools

FORMULATIONS = ("wc", "oc_a", "oc_b", "oc_c", "hy")
DENSITIES = ("frontend", "paper")
PAPER_SEQUENCES = ("0000", "0001", "0002", "0003", "0004", "0005", "0006", "0018", "0020")
KNOWN_KEYS = ("scenes", "frames", "density", "seeds", "formulations", "options", "simulate",
              "kitti")
# `dynslam solve` options a sweep sets itself for every cell.
RESERVED_OPTIONS = ("out", "gt", "check_options", "help")
# `dynslam simulate` options a sweep sets itself for every scene.
RESERVED_SIMULATE = ("out", "seq", "kitti", "seed", "frames", "synthetic", "density",
                     "check_options", "help")


class SweepFileError(Exception):
    """A sweep file that cannot be run: `str(error)` is 'FILE: KEY: problem'."""

    def __init__(self, path, key, problem):
        super().__init__(f"{path}: {key}: {problem}" if key else f"{path}: {problem}")
        self.path, self.key, self.problem = path, key, problem


@dataclasses.dataclass(frozen=True)
class Cell:
    """One solve of the sweep: a formulation of one scene, simulated with one simulation set,
    under one option set."""
    scene: str
    seed: int
    formulation: str
    options: str  # the option set's name
    simulate: str = "default"  # the simulation set's name

    @property
    def scene_dir(self):
        """Relative to the sweep's directory; the simulation set 'default' adds no suffix."""
        suffix = "" if self.simulate == "default" else f"_{self.simulate}"
        return os.path.join("cells", f"{self.scene}_s{self.seed}{suffix}")

    @property
    def key(self):
        """(scene, seed, formulation, options, simulate): the results database's key."""
        return (self.scene, self.seed, self.formulation, self.options, self.simulate)

    def row(self, **columns):
        """The cell's row of the results database: its key, its directory and `columns`."""
        return {"scene": self.scene, "seed": self.seed, "formulation": self.formulation,
                "options": self.options, "simulate": self.simulate, "cell_dir": self.cell_dir,
                **columns}

    @property
    def cell_dir(self):
        """Relative to the sweep's directory; the option set 'default' adds no suffix."""
        name = self.formulation if self.options == "default" else f"{self.formulation}_{self.options}"
        return os.path.join(self.scene_dir, name)


@dataclasses.dataclass
class Sweep:
    path: str
    scenes: list
    frames: str  # "A:B" or "" for every frame
    density: str
    seeds: list
    formulations: list
    options: dict  # name -> ["--flag=value", ...] for `dynslam solve`
    kitti: str  # absolute path of the KITTI Tracking data
    # name -> ["--flag=value", ...] for `dynslam simulate`; {"default": []} when the file has none
    simulate: dict = dataclasses.field(default_factory=lambda: {"default": []})
    # name -> the set's table as the file gives it (for the sensitivity report's axes)
    simulate_settings: dict = dataclasses.field(default_factory=lambda: {"default": {}})

    def cells(self):
        return [Cell(scene, seed, formulation, name, simulation)
                for simulation in self.simulate
                for scene in self.scenes for seed in self.seeds
                for name in self.options for formulation in self.formulations]


def load(path, kitti=None):
    """Reads and checks the sweep file at `path` (its option sets by this machine's dynslam
    command, _sweep_tools.find_cli); `kitti` overrides the data."""
    try:
        with open(path, "rb") as f:
            table = tomllib.load(f)
    except OSError as e:
        raise SweepFileError(path, "", e.strerror or str(e)) from None
    except tomllib.TOMLDecodeError as e:
        raise SweepFileError(path, "", f"not TOML: {e}") from None
    for key in table:
        if key not in KNOWN_KEYS:
            raise SweepFileError(path, key, f"unknown key (known: {', '.join(KNOWN_KEYS)})")
    for key in ("scenes", "seeds", "formulations"):
        if key not in table:
            raise SweepFileError(path, key, "missing")
    data = kitti or table.get("kitti") or _sweep_tools.embedded_kitti()
    if data is not None and not os.path.isabs(data):
        data = os.path.join(os.path.dirname(os.path.abspath(path)), data)
    sweep = Sweep(
        path=path,
        scenes=_scenes(path, table["scenes"], data),
        frames=_frames(path, table.get("frames", "")),
        density=_choice(path, "density", table.get("density", "frontend"), DENSITIES),
        seeds=_seeds(path, table["seeds"]),
        formulations=_formulations(path, table["formulations"]),
        options={},
        kitti=os.path.abspath(data) if data else "",
    )
    if sweep.density == "paper":
        for scene in sweep.scenes:
            if scene not in PAPER_SEQUENCES:
                raise SweepFileError(path, "density", f"'paper' is the density of the paper's "
                                     f"sequences ({', '.join(PAPER_SEQUENCES)}), not of {scene!r}")
    cli = _sweep_tools.find_cli()
    sweep.options = _checked_sets(path, "options", table.get("options", {"default": {}}),
                                  [cli, "solve", "-"], RESERVED_OPTIONS, "`dynslam solve`")
    simulate = table.get("simulate", {"default": {}})
    sweep.simulate = _checked_sets(path, "simulate", simulate, [cli, "simulate"],
                                   RESERVED_SIMULATE, "`dynslam simulate`")
    sweep.simulate_settings = {name: dict(settings) for name, settings in simulate.items()}
    return sweep


def _list_of_strings(path, key, value):
    if not isinstance(value, list) or not value:
        raise SweepFileError(path, key, "must be a non-empty list")
    for item in value:
        if not isinstance(item, str):
            raise SweepFileError(path, key, f"{item!r} is not a string")
    if len(set(value)) != len(value):
        raise SweepFileError(path, key, "lists an entry twice")
    return list(value)


def _scenes(path, value, kitti):
    scenes = _list_of_strings(path, "scenes", value)
    for scene in scenes:
        if scene == "synthetic":
            continue
        if kitti is None:
            raise SweepFileError(path, "kitti", "no KITTI Tracking data found: give kitti = DIR")
        if not os.path.isfile(os.path.join(kitti, "label_02", scene + ".txt")):
            raise SweepFileError(path, "scenes",
                                 f"unknown sequence {scene!r} (no {kitti}/label_02/{scene}.txt)")
    return scenes


def _frames(path, value):
    if not isinstance(value, str):
        raise SweepFileError(path, "frames", "must be a string 'A:B'")
    if value == "":
        return ""
    first, sep, last = value.partition(":")
    if not sep or not all(part == "" or part.isdigit() for part in (first, last)) or (
            first and last and int(first) >= int(last)):
        raise SweepFileError(path, "frames", f"{value!r} is not a frame range 'A:B' (A < B)")
    return value


def _choice(path, key, value, choices):
    if value not in choices:
        raise SweepFileError(path, key, f"{value!r} is not one of {', '.join(choices)}")
    return value


def _seeds(path, value):
    if isinstance(value, str):
        first, sep, last = value.partition(":")
        if not sep or not first.isdigit() or not last.isdigit() or int(first) >= int(last):
            raise SweepFileError(path, "seeds", f"{value!r} is not a range 'A:B' (A < B)")
        return list(range(int(first), int(last)))
    if not isinstance(value, list) or not value:
        raise SweepFileError(path, "seeds", "must be a non-empty list of integers or a range 'A:B'")
    for seed in value:
        if not isinstance(seed, int) or isinstance(seed, bool) or seed < 0:
            raise SweepFileError(path, "seeds", f"{seed!r} is not a non-negative integer")
    if len(set(value)) != len(value):
        raise SweepFileError(path, "seeds", "lists a seed twice")
    return list(value)


def _formulations(path, value):
    formulations = _list_of_strings(path, "formulations", value)
    for formulation in formulations:
        _choice(path, "formulations", formulation, FORMULATIONS)
    return formulations


def option_flags(options):
    """A TOML table of `dynslam solve` options (docs/OPTIONS.md) -> its flags: `max_iterations =
    5` is `--max-iterations=5`, `report = true` is `--report`, a switch `extrapolation = false`
    is `--extrapolation=off`."""
    flags = []
    for key, value in options.items():
        flag = "--" + key.replace("_", "-")
        if isinstance(value, bool):
            flags.append(flag if value else f"{flag}=off")
        else:
            flags.append(f"{flag}={value}")
    return flags


def _checked_sets(path, section, value, command, reserved, what):
    """Named sets [SECTION.NAME] of `what`'s options -> their flags, each set checked by
    `command --check-options` (exit 2 naming the problem)."""
    if not isinstance(value, dict) or not value:
        raise SweepFileError(path, section, f"must be tables [{section}.NAME] of {what} options")
    sets = {}
    for name, options in value.items():
        key = f"{section}.{name}"
        if not isinstance(options, dict):
            raise SweepFileError(path, key, f"must be a table of {what} options")
        if not name.replace("_", "").replace("-", "").isalnum():
            raise SweepFileError(path, key, "a set's name is letters, digits, '_' and '-'")
        for option, setting in options.items():
            if option.replace("-", "_") in reserved:
                raise SweepFileError(path, f"{key}.{option}", "is set by the sweep itself")
            if not isinstance(setting, (bool, int, float, str)):
                raise SweepFileError(path, f"{key}.{option}", "must be a string, number or boolean")
        flags = option_flags(options)
        check = subprocess.run([*command, "--check-options", *flags],
                               capture_output=True, text=True)
        if check.returncode != 0:
            problem = check.stderr.strip().splitlines()[0] if check.stderr.strip() else (
                f"dynslam solve exited {check.returncode}")
            raise SweepFileError(path, _named_key(key, options, problem),
                                 problem.removeprefix("error: "))
        sets[name] = flags
    return sets


def _named_key(key, options, problem):
    """`key` with the option the command's message names, when it names one of the set's."""
    for option in options:
        if "--" + option.replace("_", "-") in problem:
            return f"{key}.{option}"
    return key
