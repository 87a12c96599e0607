#!/usr/bin/env python3
"""Functions longer than LIMIT lines (issue 17: none over 80 in src/ and python/).

Usage: scripts/function_lengths.py LIMIT PATH...   e.g. scripts/function_lengths.py 80 src python

Counts from the first line of the signature to the closing brace, after blanking comments, strings and
preprocessor lines; lambdas count as part of their function, class and namespace bodies do not count. Prints
"LINES FILE:LINE SIGNATURE" per function, longest first, then "count N". Brace matching, not a C++ parser.
"""
import re, sys, os
def strip(src):
    out=[];i=0;n=len(src)
    while i<n:
        c=src[i]
        if src.startswith('//',i):
            j=src.find('\n',i); j=n if j<0 else j; out.append(' '*(j-i)); i=j
        elif src.startswith('/*',i):
            j=src.find('*/',i+2); j=n if j<0 else j+2; out.append(re.sub(r'[^\n]',' ',src[i:j])); i=j
        elif c=='R' and src.startswith('R"',i) and (i==0 or not (src[i-1].isalnum() or src[i-1]=='_')):
            m=re.match(r'R"([^(]*)\(',src[i:]); d=m.group(1); j=src.find(')'+d+'"',i); j=j+len(d)+2
            out.append('""'+re.sub(r'[^\n]',' ',src[i+2:j])); i=j
        elif c=='"' or (c=="'" and not (i>0 and src[i-1].isalnum())):
            j=i+1
            while j<n and src[j]!=c:
                j+= 2 if src[j]=='\\' else 1
            out.append(c+' '*(j-i-1)+c); i=j+1
        elif c=='#' and (i==0 or src[src.rfind('\n',0,i)+1:i].strip()==''):
            j=i
            while True:
                k=src.find('\n',j); k=n if k<0 else k
                if src[k-1]=='\\': j=k+1; continue
                break
            out.append(re.sub(r'[^\n]',' ',src[i:k])); i=k
        else: out.append(c); i+=1
    return ''.join(out)
CONTAINER=re.compile(r'^\s*(template\s*<.*>\s*)?(class|struct|union|enum|namespace|extern)\b',re.S)
# A macro invocation standing alone (NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(...)) ends a statement without a ';'.
MACRO_CALL=re.compile(r'^[ \t]*[A-Z][A-Z0-9_]*\([^;{}]*?\)[ \t]*$',re.M|re.S)
def funcs(path):
    s=MACRO_CALL.sub(lambda m: re.sub(r'[^\n]',' ',m.group(0)), strip(open(path).read())); res=[]
    i=0;n=len(s);stmt_start=0
    def match(i):
        d=0
        while i<n:
            if s[i]=='{': d+=1
            elif s[i]=='}':
                d-=1
                if d==0: return i
            i+=1
        return n-1
    depth_containers=0
    while i<n:
        c=s[i]
        if c in ';':
            stmt_start=i+1
        elif c=='}':
            stmt_start=i+1
        elif c=='{':
            stmt=s[stmt_start:i]
            if CONTAINER.match(stmt) and '(' not in stmt:
                stmt_start=i+1; i+=1; continue
            prev=stmt.rstrip()[-1:] 
            if prev=='=' or prev==',' or prev=='(' or prev=='':
                j=match(i); i=j+1; continue  # brace init
            # ctor init list?
            k=i
            if re.search(r'\)\s*(noexcept\s*)?:(?!:)',stmt):
                while prev not in (')','}'):
                    j=match(k); k=j+1
                    while s[k] != '{': k+=1
                    prev=s[j+1:k].strip()[-1:] if s[j+1:k].strip() else '}'
                    if prev==',': 
                        # find next brace
                        prev='x'; 
                        # next '{' beyond: check its predecessor
                        pre=s[j+1:k].rstrip()
                        prev=pre[-1]
            j=match(k)
            first=stmt_start+len(stmt)-len(stmt.lstrip())
            l0=s.count('\n',0,first)+1; l1=s.count('\n',0,j)+1
            name=' '.join(stmt.split())[:90]
            res.append((l1-l0+1,l0,name))
            i=j+1; stmt_start=i; continue
        i+=1
    return res
lim=int(sys.argv[1]); tot=[]
for root in sys.argv[2:]:
    paths=[root] if os.path.isfile(root) else [os.path.join(d,f) for d,_,fs in os.walk(root) for f in fs if f.endswith(('.cpp','.h'))]
    for p in sorted(paths):
        for L,l0,name in funcs(p):
            if L>lim: tot.append((L,p,l0,name))
for L,p,l0,name in sorted(tot,reverse=True): print(L,f'{p}:{l0}',name)
print('count',len(tot))
