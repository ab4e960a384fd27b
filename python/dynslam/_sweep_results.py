"""DIR/results.sqlite: one row per cell, written by the sweep's client alone (docs/SWEEPS.md).

A cell's row is replaced, never added twice, so a cell that Dask ran twice is recorded once.
Each row is committed as it arrives: a stopped sweep keeps every finished cell.
"""
import csv
import sqlite3

from ._sweep_cells import METRIC_COLUMNS, NEES_COLUMNS

KEY = ("scene", "seed", "formulation", "options", "simulate")
COLUMNS = [
    ("scene", "TEXT NOT NULL"), ("seed", "INTEGER NOT NULL"), ("formulation", "TEXT NOT NULL"),
    ("options", "TEXT NOT NULL"), ("simulate", "TEXT NOT NULL DEFAULT 'default'"),
    ("status", "TEXT NOT NULL"), ("termination", "TEXT"),
    ("steps", "INTEGER"), ("iterations", "INTEGER"), ("initial_cost", "REAL"),
    ("final_cost", "REAL"), ("solve_time_s", "REAL"), ("linear_solve_time_s", "REAL"),
    ("wall_s", "REAL"), ("weak_directions", "INTEGER"),
] + [(name, "REAL") for name in METRIC_COLUMNS + NEES_COLUMNS] + [
    ("cell_dir", "TEXT"), ("host", "TEXT"), ("version", "TEXT"), ("error", "TEXT"),
]
NAMES = [name for name, _ in COLUMNS]


def _create(connection, table):
    columns = ", ".join(f"{name} {kind}" for name, kind in COLUMNS)
    connection.execute(
        f"CREATE TABLE IF NOT EXISTS {table} ({columns}, PRIMARY KEY ({', '.join(KEY)}))")


class Results:
    def __init__(self, path):
        self.connection = sqlite3.connect(path)
        _create(self.connection, "cells")
        present = {row[1] for row in self.connection.execute("PRAGMA table_info(cells)")}
        if "simulate" not in present:
            self._add_to_key(present)
        # A database from an older dynslam: the columns added since, empty in its rows.
        for name, kind in COLUMNS:
            if name not in present:
                self.connection.execute(f"ALTER TABLE cells ADD COLUMN {name} {kind.split()[0]}")
        self.connection.commit()

    def _add_to_key(self, present):
        """A database from before simulation sets: its rows are of the set 'default', and the
        key gains `simulate` (a new table, the rows copied, in one transaction)."""
        kept = [name for name in NAMES if name in present]
        with self.connection:
            _create(self.connection, "cells_keyed")
            self.connection.execute(f"INSERT INTO cells_keyed ({', '.join(kept)}) "
                                    f"SELECT {', '.join(kept)} FROM cells")
            self.connection.execute("DROP TABLE cells")
            self.connection.execute("ALTER TABLE cells_keyed RENAME TO cells")
        present.update(NAMES)

    def close(self):
        self.connection.close()

    def finished(self):
        """The keys (KEY's order) of the cells whose status is 'ok'."""
        rows = self.connection.execute(
            f"SELECT {', '.join(KEY)} FROM cells WHERE status = 'ok'")
        return set(rows)

    def record(self, row):
        values = [row.get(name) for name in NAMES]
        self.connection.execute(
            f"INSERT OR REPLACE INTO cells ({', '.join(NAMES)}) "
            f"VALUES ({', '.join('?' * len(NAMES))})", values)
        self.connection.commit()

    def rows(self):
        """Every row as a dict, in key order."""
        cursor = self.connection.execute(
            f"SELECT {', '.join(NAMES)} FROM cells ORDER BY {', '.join(KEY)}")
        return [dict(zip(NAMES, values)) for values in cursor]

    def write_csv(self, path):
        with open(path, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=NAMES)
            writer.writeheader()
            writer.writerows(self.rows())
