import csv,glob,json,sys
root=sys.argv[1]
for f in sorted(glob.glob(root+'/runs/*/*[0-9].json')):
    d=json.load(open(f)); c=f[:-5]+'.csv'
    rows=list(csv.DictReader(open(c)))
    st=[int(r['steps']) for r in rows]; su=sum(r['success']=='1' for r in rows)
    fin=sum(st[-100:])/100
    first=next((i for i,r in enumerate(rows) if r['success']=='1'),None)
    ev=list(csv.DictReader(open(f[:-5]+'.eval.csv')))
    print('%-42s %-18s opt %4.0f AUC %5.0f (%.2fx) final %5.0f (%.2fx) goals %3d first %s leaves@100 %s end %s cpu %.0f eval %d/%d'%(d['task'], d['strategy'], d['optimal_steps'],sum(st)/len(st),sum(st)/len(st)/d['optimal_steps'],fin,fin/d['optimal_steps'],su,first,rows[99]['leaves'],rows[-1]['leaves'],d['meta']['cpu_time_s'],sum(e['success']=='1' for e in ev),len(ev)))
