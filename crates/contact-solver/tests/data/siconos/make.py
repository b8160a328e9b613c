#!/usr/bin/python3
"""Writes the `.dat` files of this folder with Siconos' own writers (frictionContact_printInFilename,
globalFrictionContact_printInFileName) from problems of our own (issue 37): dense 2D and 3D with a
non-symmetric W, sparse blocks (read from blocks_3d_in.dat, written by hand), and a global 3D
problem. Run with Debian's Python: /usr/bin/python3 crates/contact-solver/tests/data/siconos/make.py
"""
import numpy as np, siconos.numerics as sn, warnings
warnings.simplefilter("ignore")
import os
T=os.path.dirname(os.path.abspath(__file__))+"/"
p=sn.frictionContact_new_from_filename(T+"blocks_3d_in.dat")
sn.frictionContact_printInFilename(p,T+"blocks_3d.dat")
# 2D dense, non-symmetric (a skew coupling), 3 contacts
W=np.array([[2.,0.3,0.1,0.,0.,0.],[0.2,1.,0.,0.,0.,0.],[0.1,0.,3.,0.4,0.,0.],[0.,0.,0.4,1.5,0.,0.],[0.,0.,0.,0.,1.,0.25],[0.,0.,0.,0.,0.,0.5]])
q=np.array([-1.,0.5,-0.5,0.2,1.,0.]); mu=np.array([0.3,0.5,0.1])
p=sn.FrictionContactProblem(2,W,q,mu)
sn.frictionContact_printInFilename(p,T+"dense_2d.dat")
W3=np.array([[2.,0.1,0.2,0.,0.,0.],[0.1,1.5,0.,0.,0.,0.],[0.3,0.,1.,0.,0.,0.5],[0.,0.,0.,3.,0.,0.],[0.,0.,0.,0.,1.,0.],[0.,0.,0.5,0.,0.,1.]])
q3=np.array([-1.,0.5,0.25,-2.,0.,1.]); mu3=np.array([0.3,0.5])
p=sn.FrictionContactProblem(3,W3,q3,mu3)
sn.frictionContact_printInFilename(p,T+"dense_3d.dat")
M=np.diag([2.,2.,2.,1.,1.,1.]); H=np.zeros((6,3)); H[0,0]=1.; H[1,1]=1.; H[2,2]=1.; H[3,0]=-1.; H[4,1]=-0.5; H[5,2]=0.25
qg=np.array([0.,0.,-1.,0.5,0.,0.25]); b=np.array([-0.1,0.,0.])
g=sn.GlobalFrictionContactProblem(); g.dimension=3; g.numberOfContacts=1; g.M=M; g.H=H; g.q=qg; g.b=b; g.mu=np.array([0.4])
sn.globalFrictionContact_printInFileName(g,T+"global_3d.dat")
Minv=np.linalg.inv(M); print("W",(H.T@Minv@H).tolist(),"q",(H.T@Minv@qg+b).tolist())
