#!/usr/bin/env python3
"""Random contour stacks for robustness sweeps of `dfrecon reconstruct`.

Usage: scripts/random_blobs.py SEED [--harsh] > stack.slices

One to four star-shaped blobs drift through up to twelve slices, appearing
and ending mid-stack, some with a hole; contours that would cross another on
their slice are dropped, so every file is valid input. --harsh: spikier
shapes (amplitude up to 0.7, up to 11 lobes), 8 to 200 points, faster drift,
spacing 0.5 to 10 mm. docs/reconstruction.md reports a sweep over seeds.
"""
import math, random, sys
seed=int(sys.argv[1]); random.seed(seed)
harsh='--harsh' in sys.argv[2:]
nsl=random.randint(2,12); sp=random.choice([0.5,2.0,5.0,10.0] if harsh else [1.0,2.0,3.0,5.0])
# a few blobs drifting through z, appearing/disappearing, with holes sometimes
blobs=[]
for b in range(random.randint(1,4)):
    z0=random.randint(0,nsl-1); z1=random.randint(z0,nsl-1)
    blobs.append(dict(z0=z0,z1=z1,cx=random.uniform(-15,15),cy=random.uniform(-15,15),
        vx=random.uniform(-6,6) if harsh else random.uniform(-3,3),vy=random.uniform(-6,6) if harsh else random.uniform(-3,3),r=random.uniform(3,10),
        hole=random.random()<0.3, k=random.randint(2,11 if harsh else 6), amp=random.uniform(0,0.7 if harsh else 0.35), ph=random.uniform(0,6)))
def star(cx,cy,r,k,amp,ph,n,cw=False):
    pts=[]
    for i in range(n):
        t=2*math.pi*i/n*(-1 if cw else 1)
        rr=r*(1+amp*math.sin(k*t+ph))
        pts.append((cx+rr*math.cos(t),cy+rr*math.sin(t)))
    return pts
def inside(p,poly):
    x,y=p; c=False
    for i in range(len(poly)):
        x1,y1=poly[i]; x2,y2=poly[(i+1)%len(poly)]
        if (y1>y)!=(y2>y) and x < x1+(y-y1)*(x2-x1)/(y2-y1): c=not c
    return c
def segs_cross(a,b,c,d):
    def o(p,q,r): return (q[0]-p[0])*(r[1]-p[1])-(q[1]-p[1])*(r[0]-p[0])
    return o(a,b,c)*o(a,b,d)<0 and o(c,d,a)*o(c,d,b)<0
def cross_any(P,Q):
    for i in range(len(P)):
        for j in range(len(Q)):
            if segs_cross(P[i],P[(i+1)%len(P)],Q[j],Q[(j+1)%len(Q)]): return True
    return False
out=["dfrecon-slices 1","units mm","roi blob"]
for s in range(nsl):
    cs=[]
    for b in blobs:
        if not (b['z0']<=s<=b['z1']): continue
        cx=b['cx']+b['vx']*s; cy=b['cy']+b['vy']*s
        n=random.randint(8,200) if harsh else random.randint(20,80)
        c=star(cx,cy,b['r']*(0.8+0.2*math.sin(s)),b['k'],b['amp'],b['ph']+0.3*s,n)
        if any(cross_any(c,o) or inside(c[0],o) or inside(o[0],c) for o in cs): continue
        cs.append(c)
        if b['hole'] and b['amp']<0.2:
            h=star(cx+0.2,cy,b['r']*0.35,3,0.1,0,24,cw=True)
            cs.append(h)
    if not cs: continue
    out.append("slice %g"%(s*sp))
    for c in cs:
        out.append("contour %d"%len(c))
        out += ["%.6f %.6f"%p for p in c]
sys.stdout.write("\n".join(out)+"\n")
