import sys; sys.path.insert(0,'/tmp')
from pfm import pfm
import glob, re
px=[(723,153),(634,245)]
for K in sys.argv[1:]:
  for s in (0,1):
    for f in (0,1,2):
      try:
        a=pfm(f'/tmp/dbg/k{K}_s{s}_f{f}_keep.pfm'); b=pfm(f'/tmp/dbg/k{K}_s{s}_f{f}_cull.pfm')
      except FileNotFoundError: continue
      for x,y in px:
        va=a[y,x]*2; vb=b[y,x]*2
        print(f'K{K} s{s} f{f} ({x},{y}) keep {va.tolist()} cull {vb.tolist()}', '' if (va==vb).all() else '  <-- DIFF')
