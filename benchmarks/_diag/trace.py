import glob, os, shutil, sys, time
sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
import jax, jax.numpy as jnp
jax.config.update("jax_enable_x64", True)
import roughcontact as rc
from hardwall import surface
N = int(os.environ.get("N", "4096")); OUT = os.environ.get("OUT", "/tmp/tr")
h = jnp.asarray(surface(N, 1)); sub = rc.Substrate((N, N))
p0 = jnp.full((N, N), 1e-3)
law = rc.SmoothLJ93.from_adhesion_length(0.005)
d = rc.solve(h, sub, rc.HardWall(), load=5e-4).offset
for name, run in (("hw", lambda: rc.solve(h, sub, rc.HardWall(), load=1e-3, initial=p0)),
                  ("lj", lambda: rc.solve(h, sub, law, offset=d + 1, max_iter=40))):
    run()
    tmp = os.path.join(OUT, "t_" + name)
    with jax.profiler.trace(tmp):
        t = time.perf_counter(); r = run(); print(name, r.iterations, time.perf_counter() - t, flush=True)
    for f in glob.glob(os.path.join(tmp, "**", "*.trace.json.gz"), recursive=True):
        shutil.move(f, os.path.join(OUT, name + ".trace.json.gz"))
    shutil.rmtree(tmp)
