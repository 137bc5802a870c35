/* Paul Heckbert's business-card ray tracer ("minray", 1987; Graphics Gems IV,
 * "A Minimal Ray Tracer"), the reference program of lamplight's `business-card`
 * scene and of tests/business_card.rs.
 *
 * The text below is the original card. The lecture's transcription lost
 * decimal points and numbers in the sphere table, a `>` in intersect(), a `;`
 * before `if(d<0)`, a `+` in `yx++/32` and a `.` in `%.0f`; all of these are
 * restored here from the published copies (see the module doc of
 * src/builtin/business_card.rs for the evidence). Two changes to the card:
 *
 * 1. printf("%.0f %.0f %.0f\n",U) -> printf("%.0f %.0f %.0f\n",U.x,U.y,U.z):
 *    a struct passed through printf's varargs only worked on 1987 stack-based
 *    ABIs; on x86-64 and AArch64 printf would read unrelated registers.
 * 2. vcomb(s->kl,U,black) -> vcomb(s->kl,s->color,black) in trace's return:
 *    U was set to s->color just before, but the same argument list calls trace
 *    twice, and trace and intersect overwrite the global U. C leaves the order
 *    of argument evaluation open: gcc evaluates right to left and reads
 *    s->color (gcc 12, -O0 and -O2, prints byte-identical images with and
 *    without this change); a compiler going left to right would read a stale
 *    vector. The change pins the emission kl*color that the card means.
 *
 * Build: cc -std=gnu89 -ffp-contract=off -w heckbert.c -lm
 * (K&R definitions and implicit int need gnu89; no fused multiply-adds, so
 * every operation is rounded as written.)
 * Output: "W H", then per pixel (row by row, top first) the rounded
 * 255 * radiance of each channel, unclamped.
 */
typedef struct{double x,y,z}vec;vec U,black,amb={.02,.02,.02};struct sphere{
vec cen,color;double rad,kd,ks,kt,kl,ir}*s,*best,sph[]={0.,6.,.5,1.,1.,1.,.9,
.05,.2,.85,0.,1.7,-1.,8.,-.5,1.,.5,.2,1.,.7,.3,0.,.05,1.2,1.,8.,-.5,.1,.8,.8,
1.,.3,.7,0.,0.,1.2,3.,-6.,15.,1.,.8,1.,7.,0.,0.,0.,.6,1.5,-3.,-3.,12.,.8,1.,
1.,5.,0.,0.,0.,.5,1.5,};yx;double u,b,tmin,sqrt(),tan();double vdot(A,B)vec A
,B;{return A.x*B.x+A.y*B.y+A.z*B.z;}vec vcomb(a,A,B)double a;vec A,B;{B.x+=a*
A.x;B.y+=a*A.y;B.z+=a*A.z;return B;}vec vunit(A)vec A;{return vcomb(1./sqrt(
vdot(A,A)),A,black);}struct sphere*intersect(P,D)vec P,D;{best=0;tmin=1e30;s=
sph+5;while(s-->sph)b=vdot(D,U=vcomb(-1.,P,s->cen)),u=b*b-vdot(U,U)+s->rad*s
->rad,u=u>0?sqrt(u):1e31,u=b-u>1e-7?b-u:b+u,tmin=u>=1e-7&&u<tmin?best=s,u:
tmin;return best;}vec trace(level,P,D)vec P,D;{double d,eta,e;vec N,color;
struct sphere*s,*l;if(!level--)return black;if(s=intersect(P,D));else return
amb;color=amb;eta=s->ir;d= -vdot(D,N=vunit(vcomb(-1.,P=vcomb(tmin,D,P),s->cen
)));if(d<0)N=vcomb(-1.,N,black),eta=1/eta,d= -d;l=sph+5;while(l-->sph)if((e=l
->kl*vdot(N,U=vunit(vcomb(-1.,P,l->cen))))>0&&intersect(P,U)==l)color=vcomb(e
,l->color,color);U=s->color;color.x*=U.x;color.y*=U.y;color.z*=U.z;e=1-eta*
eta*(1-d*d);return vcomb(s->kt,e>0?trace(level,P,vcomb(eta,D,vcomb(eta*d-sqrt
(e),N,black))):black,vcomb(s->ks,trace(level,P,vcomb(2*d,N,D)),vcomb(s->kd,
color,vcomb(s->kl,s->color,black))));}main(){printf("%d %d\n",32,32);while(yx<32*32)
U.x=yx%32-32/2,U.z=32/2-yx++/32,U.y=32/2/tan(25/114.5915590261),U=vcomb(255.,
trace(3,black,vunit(U)),black),printf("%.0f %.0f %.0f\n",U.x,U.y,U.z);}/*minray!*/
