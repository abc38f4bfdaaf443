import numpy as np, time
from cablestudy.statics import STATIC_SOLVERS, StaticProblem, EndCondition, Medium
from tests.stress.test_statics_property import make_line
L=221.22999672958395
prob = StaticProblem(line=make_line(L, -0.2, 1e7, []),
    medium=Medium(density=1025.0, gravity=9.8, current_z=np.array([-L-10, 10.0]),
        current_velocity=np.array([[1.112553405138498, 0.43793058739907026, 0.0],[1.1956413670766672, 0.0, 0.0]])),
    end_a=EndCondition(kind='fixed', position=np.zeros(3)),
    end_b=EndCondition(kind='fixed', position=np.array([130.09207548635544, 0.0, 26.370969241236015])),
    n_nodes=31, tolerance=1e-9)
for m in ("catenary",):
    t=time.perf_counter(); r=STATIC_SOLVERS[m].solve(prob); print(m, r.status, r.message, r.iterations, f"{time.perf_counter()-t:.2f}s", r.force_a)
