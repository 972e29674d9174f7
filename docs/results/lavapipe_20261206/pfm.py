import numpy as np, sys
def pfm(p):
    with open(p,'rb') as f:
        f.readline(); w,h = map(int,f.readline().split()); sc=float(f.readline()); d=np.frombuffer(f.read(), dtype='<f4' if sc<0 else '>f4')
    return d.reshape(h,w,3)
if __name__ == '__main__':
    a,b = pfm(sys.argv[1]), pfm(sys.argv[2])
    ys,xs = np.nonzero(np.any(a!=b,axis=2))
    print(len(ys), 'pixels differ')
    for y,x in list(zip(ys,xs))[:20]: print('x',x,'y',y, a[y,x], b[y,x])
