#!/usr/bin/env python3
# Interim check (issue #18 item 3 asks for this inside `globalvis photons --compare`): compares a
# `radiosity` run with a `photons` run of the same scene patch by patch, counting what the
# built-in comparison leaves out. Usage: compare-photons.py RADIOSITY_DIR PHOTONS_DIR PHOTON_COUNT
# Solver vs photons on the same patches.obj: area-weighted L2 of B-Ke, leaks (solution lit, tracer
# expected >= 10 hits, got none), counts of channels with no photons.
import sys, math
rdir, pdir, nphot = sys.argv[1], sys.argv[2], float(sys.argv[3])
def load_obj(d):
    V=[];F=[];mats={};cur=None;M={}
    for line in open(d+'/patches.mtl'):
        t=line.split()
        if not t: continue
        if t[0]=='newmtl': cur=t[1]; M[cur]={'Kd':(0,0,0),'Ke':(0,0,0)}
        elif t[0] in('Kd','Ke'): M[cur][t[0]]=tuple(map(float,t[1:4]))
    for line in open(d+'/patches.obj'):
        t=line.split()
        if not t: continue
        if t[0]=='v': V.append(tuple(map(float,t[1:4])))
        elif t[0]=='usemtl': cur=t[1]
        elif t[0]=='f': F.append(([V[int(x.split('/')[0])-1] for x in t[1:]],cur))
    return F,M
def area(f):
    n=[0,0,0]
    for i in range(1,len(f)-1):
        a=[f[i][k]-f[0][k] for k in range(3)]; b=[f[i+1][k]-f[0][k] for k in range(3)]
        c=(a[1]*b[2]-a[2]*b[1],a[2]*b[0]-a[0]*b[2],a[0]*b[1]-a[1]*b[0]); n=[n[k]+c[k] for k in range(3)]
    return 0.5*math.sqrt(sum(x*x for x in n))
def rad(d):
    out={}
    for line in open(d+'/radiosity.txt'):
        if line.startswith('#'): continue
        t=line.split(); out[int(t[0])]=tuple(map(float,t[1:4]))
    return out
F,M=load_obj(rdir); F2,_=load_obj(pdir)
assert len(F)==len(F2), (len(F),len(F2))
B=rad(rdir); P=rad(pdir)
A=[area(f) for f,_ in F]
phi=[sum(A[i]*M[m]['Ke'][c] for i,(f,m) in enumerate(F)) for c in range(3)]  # emitted power per channel
num=den=0; leaks=[]; nophot=0
for i,(f,m) in enumerate(F):
    kd=M[m]['Kd']; ke=M[m]['Ke']
    for c in range(3):
        b=B[i][c]-ke[c]; p=P[i][c]-ke[c]
        num+=A[i]*(b-p)**2; den+=A[i]*p**2
        if p<=0:
            nophot+=1
            if b>0 and kd[c]>0:
                # expected photon hits on the patch at the solution's value (per channel)
                exp=(b/kd[c])*A[i]/(sum(phi)/nphot) if sum(phi)>0 else 0  # photons share one power
                if exp>=10: leaks.append((i,c,b,exp))
print('patches',len(F),'area-weighted L2 of B-Ke: %.2f %%'%(100*math.sqrt(num/den)))
print('channels with no photon:',nophot,'of',3*len(F))
lp=sorted(set(i for i,_,_,_ in leaks))
print('leak patches (solution lit, >=10 photon hits expected, 0 received):',len(lp), lp[:10])
