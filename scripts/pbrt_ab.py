#!/usr/bin/env python3
"""A/B of spectrace against pbrt-v4 on small ad-hoc pbrt-v4 scenes: each case is rendered by
both (two seeds each, SPP samples, RES × RES pixels) and the mean Y over the object's pixels
(those more than 2 % off the corners' value) is printed with its standard error and the z of
the difference. pbrt-v4's Y = 0.2126 R + 0.7152 G + 0.0722 B of its film; spectrace's Y / 683.

The default cases measure pbrt-v4's layered BSDF: its f() (used by next-event estimation, so
under the sun) against its sampler (the only estimator pbrt-v4 uses for a uniform sky).

Usage: build pbrt-v4 (../shared/tools/pbrt/build_pbrt.sh) and spectrace (cargo build
--release); pip install numpy OpenImageIO;
SPP=1024 python3 scripts/pbrt_ab.py [cases.py]   (a cases file calls run(name, body))
"""
import os
import subprocess
import sys
import tempfile

import numpy as np
import OpenImageIO as oiio
PBRT=os.path.expanduser("~/.cache/pbrt-v4/bin/pbrt"); 
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ST = os.path.join(ROOT, "target", "release", "spectrace")
TMP = tempfile.mkdtemp()
SPP=int(os.environ.get("SPP","1024")); RES=int(os.environ.get("RES","16"))
HEAD=f'''LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" [30]
Film "rgb" "integer xresolution" {RES} "integer yresolution" {RES}
Sampler "zsobol" "integer pixelsamples" {SPP}
Integrator "path" "integer maxdepth" 5
WorldBegin
'''
SKY='LightSource "infinite" "blackbody L" 5000 "float scale" 2\n'
SUN='LightSource "distant" "point3 from" [2 3 4] "point3 to" [0 0 0] "blackbody L" 5500 "float scale" 3\n'
def read(path, ch):
    i=oiio.ImageInput.open(path); spec=i.spec(); a=np.array(i.read_image(format="float")); i.close()
    names=list(spec.channelnames)
    if ch=="pbrt":
        return 0.2126*a[...,0]+0.7152*a[...,1]+0.0722*a[...,2]
    return a[...,names.index("Y")]/683.002
def run(name, body):
    text=HEAD+body
    d=os.path.join(TMP, name); os.makedirs(d,exist_ok=True)
    sc=f"{d}/s.pbrt"; open(sc,"w").write(text)
    P=[];S=[]
    for seed in (1,2):
        subprocess.run([PBRT,"--quiet","--seed",str(seed),"--outfile",f"{d}/p{seed}.exr",sc],check=True,cwd=d)
        P.append(read(f"{d}/p{seed}.exr","pbrt"))
        subprocess.run([ST,"render",sc,"-o",f"{d}/s{seed}.exr","--png",f"{d}/s{seed}.png","--seed",str(seed),"--spp",str(SPP)],check=True,cwd=d,capture_output=True)
        S.append(read(f"{d}/s{seed}.exr","st"))
    img=(P[0]+P[1])/2; bg=np.median([img[0,0],img[0,-1],img[-1,0],img[-1,-1]])
    m=np.abs(img-bg)>0.02*abs(bg)
    def st(a,b):
        n=m.sum(); return ((a+b)/2)[m].mean(), (a-b)[m].std()/2/np.sqrt(n)
    (p,pe),(s,se)=st(*P),st(*S)
    print(f"{name}: st {s:.5f}±{se:.5f} pbrt {p:.5f}±{pe:.5f} {100*(s/p-1):+.2f}% z {(s-p)/np.hypot(pe,se):+.1f}", flush=True)
DEFAULT = """
sph = 'Shape "sphere" "float radius" 1\\n'
rough = 'Material "coateddiffuse" "rgb reflectance" [0.7 0.3 0.2] "float roughness" 0.05\\n'
run("coateddiffuse_rough_sun_only", SUN + rough + sph)
run("coateddiffuse_rough_sky_only", SKY + rough + sph)
"""

if __name__ == "__main__":
    exec(open(sys.argv[1]).read() if len(sys.argv) > 1 else DEFAULT)
